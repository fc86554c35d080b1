"""What ships with a compiled core besides its Verilog: the files a user's own flow reads.

:mod:`~phongfx.deliver.constraints` (the clock constraint as SDC, ECP5 LPF and an iCE40
nextpnr script) and :mod:`~phongfx.deliver.fusesoc` (a FuseSoC CAPI2 core file with the
RTL, the testbench and their targets).
"""
