"""The simulated top of the fast back end (:mod:`phongfx.sim.fast_backend`): word ports around a block.

The C++ checker drives one input word array and reads one output word array per cycle, 32-bit
words least significant first, as Verilator's ``VlWide`` stores a wide port: :func:`wrapper`
pads ``{i.payload, i.valid}`` and ``{o.payload, o.valid}`` to at least :data:`MIN_WORDS` words
(:func:`words_of`), so that both ports are ``VlWide`` whatever the block.
"""

__all__ = ["MIN_WORDS", "words_of", "wrapper", "is_stream"]

#: Words of every port at least: over 64 bits, every port is a ``VlWide``.
MIN_WORDS = 3


def words_of(bits):
    """32-bit words of a port ``bits`` wide (at least :data:`MIN_WORDS`)."""
    return max(MIN_WORDS, (bits + 31) // 32)


def wrapper(module, in_width, out_width, stream=False):
    """Verilog of the simulation top ``<module>_fast``: word ports around block ``module``.

    ``i_word`` is ``{pad, i.payload, i.valid}`` and ``o_word`` ``{0, o.payload, o.valid}``,
    each :func:`words_of` 32-bit words, combinational both ways.  ``ctl`` is ``{rst, o.ready}``
    and ``i_ready`` the design's ``i.ready`` for a ``stream`` design (a
    :class:`~phongfx.hdl.handshake.Handshake`); a plain block ignores ``ctl``, its reset
    tied low so that Verilator folds it away, and ``i_ready`` is 1.
    """
    ni, no = words_of(in_width + 1), words_of(out_width + 1)
    pad = 32 * no - out_width - 1
    tie = f"  assign o_word[{32 * no - 1}:{out_width + 1}] = {pad}'d0;\n" if pad else ""
    if stream:
        ports = ".clk(clk), .rst(ctl[1]),\n    .i__valid(i_word[0]), .i__ready(i_ready), "
        out_ready = ", .o__ready(ctl[0])"
    else:
        ports = ".clk(clk), .rst(1'b0),\n    .i__valid(i_word[0]), "
        out_ready = ""
        tie += "  assign i_ready = 1'b1;\n"
    return f"""
module {module}_fast(clk, ctl, i_word, o_word, i_ready);
  input clk;
  input [1:0] ctl;
  input [{32 * ni - 1}:0] i_word;
  output [{32 * no - 1}:0] o_word;
  output i_ready;
  {module} dut (
    {ports}.i__payload(i_word[{in_width}:1]),
    .o__valid(o_word[0]){out_ready}, .o__payload(o_word[{out_width}:1])
  );
{tie}endmodule
"""


def is_stream(component):
    """Whether ``component``'s ``i`` has a ``ready`` (a Handshake), which the top must drive."""
    return "ready" in component.i.signature.members
