// Two specgen units in a top of one's own (written by scripts/bench_two_units.sh):
// `pair_quadratic` and `pair_blinn` fed by plain registers and read by plain registers, no serial wrapper. The registers stand for
// the user's pipeline: `src` is a shift register the pins `din` feed; the outputs' parity is
// folded four bits a register level to the pin `dout` (so that nothing is optimized away).
`timescale 1ns / 1ps
`default_nettype none
module pair_plain_top (
    input  wire       clk,
    input  wire [3:0] din,
    output wire       dout
);
    reg  [103:0] src = 104'd0;      // the user's data, shifted in from the pins
    reg  [103:0] in_reg = 104'd0;   // every unit input from a plain register
    wire [83:0] unit_out;
    reg  [83:0] out_reg = 84'd0; // every unit output into a plain register
    wire [83:0] fold0_in = out_reg;
    reg  [20:0] fold0 = 21'd0;
    wire [23:0] fold1_in = {3'd0, fold0};
    reg  [5:0] fold1 = 6'd0;
    wire [7:0] fold2_in = {2'd0, fold1};
    reg  [1:0] fold2 = 2'd0;
    wire [3:0] fold3_in = {2'd0, fold2};
    reg  [0:0] fold3 = 1'd0;
    integer i;
    always @(posedge clk) begin
        src <= {src[99:0], din};
        in_reg <= src;
        out_reg <= unit_out;
        for (i = 0; i < 21; i = i + 1) fold0[i] <= ^fold0_in[4 * i +: 4];
        for (i = 0; i < 6; i = i + 1) fold1[i] <= ^fold1_in[4 * i +: 4];
        for (i = 0; i < 2; i = i + 1) fold2[i] <= ^fold2_in[4 * i +: 4];
        for (i = 0; i < 1; i = i + 1) fold3[i] <= ^fold3_in[4 * i +: 4];
    end
    assign dout = fold3[0];
    pair_quadratic u_pair_quadratic (.clk(clk), .rst(in_reg[0:0]), .in_valid(in_reg[1:1]), .cos_g(in_reg[17:2]), .n(in_reg[27:18]), .ks_r(in_reg[35:28]), .ks_g(in_reg[43:36]), .ks_b(in_reg[51:44]), .out_valid(unit_out[0:0]), .spec_r(unit_out[8:1]), .spec_g(unit_out[16:9]), .spec_b(unit_out[24:17]), .intensity(unit_out[40:25]), .done(unit_out[41:41]));
    pair_blinn u_pair_blinn (.clk(clk), .rst(in_reg[52:52]), .in_valid(in_reg[53:53]), .cos_g(in_reg[69:54]), .n(in_reg[79:70]), .ks_r(in_reg[87:80]), .ks_g(in_reg[95:88]), .ks_b(in_reg[103:96]), .out_valid(unit_out[42:42]), .spec_r(unit_out[50:43]), .spec_g(unit_out[58:51]), .spec_b(unit_out[66:59]), .intensity(unit_out[82:67]), .done(unit_out[83:83]));
endmodule
`default_nettype wire
