
module difference_synth(clk, rst, si, load, so);
  input clk, rst, si, load;
  output so;
  reg [85:0] in_shift = 0;
  reg [26:0] out_shift = 0;
  wire o_valid;
  wire [25:0] o_payload;
  difference dut (
    .clk(clk), .rst(rst),
    .i__valid(in_shift[0]), .i__payload(in_shift[85:1]),
    .o__valid(o_valid), .o__payload(o_payload)
  );
  assign so = out_shift[26];
  always @(posedge clk) begin
    in_shift <= {in_shift[84:0], si};
    out_shift <= load ? {o_payload, o_valid} : {out_shift[25:0], 1'b0};
  end
endmodule
