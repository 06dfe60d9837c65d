// DP16KD (Lattice ECP5 16-kbit block RAM) used as a ROM: a behavioural simulation model,
// written by specgen {{ version }} beside a unit generated with --target ecp5 whose table is in
// block RAM, and used by `specgen synth --verify --target ecp5`. For simulation only: never
// give it to synthesis. yosys (0.23, and 0.70) ships DP16KD only as an empty
// black box, so a mapped ECP5 netlist with a table in block RAM cannot be simulated with
// yosys's models alone. The contents follow yosys's ecp5/brams_map.v: 18-bit word k lives in
// INITVAL_(k/16) bits [(k%16)*20 +: 18]. Both ports read synchronously (CLK, CE, chip select
// by CSDECODE) in 18- or 9-bit width, with REGMODE NOREG or OUTREG and a reset that clears
// the output. A write, another width, or another setting stops the simulation with an error
// rather than computing something else. Ports as in yosys's ecp5/cells_sim.v.
{%- raw %}
`timescale 1ns / 1ps
// Guarded: every ECP5 unit brings this model, and a design with several units reads it once.
`ifndef SPECGEN_ECP5_DP16KD_SIM
`define SPECGEN_ECP5_DP16KD_SIM
// A cell model: its ports are the primitive's, most unused here, its file is not its name, and
// it compares string parameters of any length.
/* verilator lint_off UNUSEDSIGNAL */
/* verilator lint_off UNUSEDPARAM */
/* verilator lint_off DECLFILENAME */
/* verilator lint_off WIDTH */
module DP16KD(
  input DIA17, DIA16, DIA15, DIA14, DIA13, DIA12, DIA11, DIA10, DIA9, DIA8, DIA7, DIA6, DIA5, DIA4, DIA3, DIA2, DIA1, DIA0,
  input ADA13, ADA12, ADA11, ADA10, ADA9, ADA8, ADA7, ADA6, ADA5, ADA4, ADA3, ADA2, ADA1, ADA0,
  input CEA, OCEA, CLKA, WEA, RSTA,
  input CSA2, CSA1, CSA0,
  output DOA17, DOA16, DOA15, DOA14, DOA13, DOA12, DOA11, DOA10, DOA9, DOA8, DOA7, DOA6, DOA5, DOA4, DOA3, DOA2, DOA1, DOA0,

  input DIB17, DIB16, DIB15, DIB14, DIB13, DIB12, DIB11, DIB10, DIB9, DIB8, DIB7, DIB6, DIB5, DIB4, DIB3, DIB2, DIB1, DIB0,
  input ADB13, ADB12, ADB11, ADB10, ADB9, ADB8, ADB7, ADB6, ADB5, ADB4, ADB3, ADB2, ADB1, ADB0,
  input CEB, OCEB, CLKB, WEB, RSTB,
  input CSB2, CSB1, CSB0,
  output DOB17, DOB16, DOB15, DOB14, DOB13, DOB12, DOB11, DOB10, DOB9, DOB8, DOB7, DOB6, DOB5, DOB4, DOB3, DOB2, DOB1, DOB0
);
    parameter DATA_WIDTH_A = 18;
    parameter DATA_WIDTH_B = 18;
    parameter REGMODE_A = "NOREG";
    parameter REGMODE_B = "NOREG";
    parameter RESETMODE = "SYNC";
    parameter ASYNC_RESET_RELEASE = "SYNC";
    parameter CSDECODE_A = "0b000";
    parameter CSDECODE_B = "0b000";
    parameter WRITEMODE_A = "NORMAL";
    parameter WRITEMODE_B = "NORMAL";
    parameter DIA17MUX = "DIA17";
    parameter CLKAMUX = "CLKA";
    parameter CLKBMUX = "CLKB";
    parameter GSR = "ENABLED";
    parameter WID = 0;
    parameter INIT_DATA = "STATIC";
    parameter INITVAL_00 = 320'h0;
    parameter INITVAL_01 = 320'h0;
    parameter INITVAL_02 = 320'h0;
    parameter INITVAL_03 = 320'h0;
    parameter INITVAL_04 = 320'h0;
    parameter INITVAL_05 = 320'h0;
    parameter INITVAL_06 = 320'h0;
    parameter INITVAL_07 = 320'h0;
    parameter INITVAL_08 = 320'h0;
    parameter INITVAL_09 = 320'h0;
    parameter INITVAL_0A = 320'h0;
    parameter INITVAL_0B = 320'h0;
    parameter INITVAL_0C = 320'h0;
    parameter INITVAL_0D = 320'h0;
    parameter INITVAL_0E = 320'h0;
    parameter INITVAL_0F = 320'h0;
    parameter INITVAL_10 = 320'h0;
    parameter INITVAL_11 = 320'h0;
    parameter INITVAL_12 = 320'h0;
    parameter INITVAL_13 = 320'h0;
    parameter INITVAL_14 = 320'h0;
    parameter INITVAL_15 = 320'h0;
    parameter INITVAL_16 = 320'h0;
    parameter INITVAL_17 = 320'h0;
    parameter INITVAL_18 = 320'h0;
    parameter INITVAL_19 = 320'h0;
    parameter INITVAL_1A = 320'h0;
    parameter INITVAL_1B = 320'h0;
    parameter INITVAL_1C = 320'h0;
    parameter INITVAL_1D = 320'h0;
    parameter INITVAL_1E = 320'h0;
    parameter INITVAL_1F = 320'h0;
    parameter INITVAL_20 = 320'h0;
    parameter INITVAL_21 = 320'h0;
    parameter INITVAL_22 = 320'h0;
    parameter INITVAL_23 = 320'h0;
    parameter INITVAL_24 = 320'h0;
    parameter INITVAL_25 = 320'h0;
    parameter INITVAL_26 = 320'h0;
    parameter INITVAL_27 = 320'h0;
    parameter INITVAL_28 = 320'h0;
    parameter INITVAL_29 = 320'h0;
    parameter INITVAL_2A = 320'h0;
    parameter INITVAL_2B = 320'h0;
    parameter INITVAL_2C = 320'h0;
    parameter INITVAL_2D = 320'h0;
    parameter INITVAL_2E = 320'h0;
    parameter INITVAL_2F = 320'h0;
    parameter INITVAL_30 = 320'h0;
    parameter INITVAL_31 = 320'h0;
    parameter INITVAL_32 = 320'h0;
    parameter INITVAL_33 = 320'h0;
    parameter INITVAL_34 = 320'h0;
    parameter INITVAL_35 = 320'h0;
    parameter INITVAL_36 = 320'h0;
    parameter INITVAL_37 = 320'h0;
    parameter INITVAL_38 = 320'h0;
    parameter INITVAL_39 = 320'h0;
    parameter INITVAL_3A = 320'h0;
    parameter INITVAL_3B = 320'h0;
    parameter INITVAL_3C = 320'h0;
    parameter INITVAL_3D = 320'h0;
    parameter INITVAL_3E = 320'h0;
    parameter INITVAL_3F = 320'h0;

    localparam [20479:0] INIT = {INITVAL_3F, INITVAL_3E, INITVAL_3D, INITVAL_3C, INITVAL_3B, INITVAL_3A, INITVAL_39, INITVAL_38, INITVAL_37, INITVAL_36, INITVAL_35, INITVAL_34, INITVAL_33, INITVAL_32, INITVAL_31, INITVAL_30, INITVAL_2F, INITVAL_2E, INITVAL_2D, INITVAL_2C, INITVAL_2B, INITVAL_2A, INITVAL_29, INITVAL_28, INITVAL_27, INITVAL_26, INITVAL_25, INITVAL_24, INITVAL_23, INITVAL_22, INITVAL_21, INITVAL_20, INITVAL_1F, INITVAL_1E, INITVAL_1D, INITVAL_1C, INITVAL_1B, INITVAL_1A, INITVAL_19, INITVAL_18, INITVAL_17, INITVAL_16, INITVAL_15, INITVAL_14, INITVAL_13, INITVAL_12, INITVAL_11, INITVAL_10, INITVAL_0F, INITVAL_0E, INITVAL_0D, INITVAL_0C, INITVAL_0B, INITVAL_0A, INITVAL_09, INITVAL_08, INITVAL_07, INITVAL_06, INITVAL_05, INITVAL_04, INITVAL_03, INITVAL_02, INITVAL_01, INITVAL_00};
`ifndef SYNTHESIS  // (a simulation check: `specgen prove` reads the model with SYNTHESIS)
    initial begin
        if (!(DATA_WIDTH_A == 18 || DATA_WIDTH_A == 9) || !(DATA_WIDTH_B == 18 || DATA_WIDTH_B == 9)
                || !(REGMODE_A == "NOREG" || REGMODE_A == "OUTREG") || !(REGMODE_B == "NOREG" || REGMODE_B == "OUTREG")
                || CLKAMUX != "CLKA" || CLKBMUX != "CLKB") begin
            $fatal(1, "%m: DP16KD setting outside the specgen model (widths 18 or 9, REGMODE NOREG or OUTREG, plain clocks)");
        end
    end
`endif
    // 18-bit word k of the contents, and 9-bit half h
    function [17:0] word(input [9:0] k);
        word = INIT[k[9:4] * 320 + k[3:0] * 20 +: 18];
    endfunction
    function [8:0] half(input [10:0] h);
        reg [17:0] w;
        begin
            w = word(h[10:1]);
            half = h[0] ? w[17:9] : w[8:0];
        end
    endfunction

    // ---- port A: synchronous read (CLKA, CEA), optional output register (OCEA) ----
    wire [13:0] ad_a = {ADA13, ADA12, ADA11, ADA10, ADA9, ADA8, ADA7, ADA6, ADA5, ADA4, ADA3, ADA2, ADA1, ADA0};
    wire        cs_a = {CSA2, CSA1, CSA0} == {CSDECODE_A[16], CSDECODE_A[8], CSDECODE_A[0]};
    reg  [17:0] rd_a, out_a;
    always @(posedge CLKA) begin
`ifndef SYNTHESIS  // (a simulation check: `specgen prove` reads the model with SYNTHESIS)
        if (WEA === 1'b1 && CEA === 1'b1 && cs_a) begin
            $fatal(1, "%m: DP16KD write on port A: the specgen model is read-only (ROMs)");
        end
`endif
        if (RSTA === 1'b1) rd_a <= 18'd0;
        else if (CEA === 1'b1 && cs_a) rd_a <= DATA_WIDTH_A == 18 ? word(ad_a[13:4]) : {9'd0, half(ad_a[13:3])};
        if (RSTA === 1'b1) out_a <= 18'd0;
        else if (OCEA === 1'b1) out_a <= rd_a;
    end
    assign {DOA17, DOA16, DOA15, DOA14, DOA13, DOA12, DOA11, DOA10, DOA9, DOA8, DOA7, DOA6, DOA5, DOA4, DOA3, DOA2, DOA1, DOA0} = REGMODE_A == "OUTREG" ? out_a : rd_a;

    // ---- port B: synchronous read (CLKB, CEB), optional output register (OCEB) ----
    wire [13:0] ad_b = {ADB13, ADB12, ADB11, ADB10, ADB9, ADB8, ADB7, ADB6, ADB5, ADB4, ADB3, ADB2, ADB1, ADB0};
    wire        cs_b = {CSB2, CSB1, CSB0} == {CSDECODE_B[16], CSDECODE_B[8], CSDECODE_B[0]};
    reg  [17:0] rd_b, out_b;
    always @(posedge CLKB) begin
`ifndef SYNTHESIS  // (a simulation check: `specgen prove` reads the model with SYNTHESIS)
        if (WEB === 1'b1 && CEB === 1'b1 && cs_b) begin
            $fatal(1, "%m: DP16KD write on port B: the specgen model is read-only (ROMs)");
        end
`endif
        if (RSTB === 1'b1) rd_b <= 18'd0;
        else if (CEB === 1'b1 && cs_b) rd_b <= DATA_WIDTH_B == 18 ? word(ad_b[13:4]) : {9'd0, half(ad_b[13:3])};
        if (RSTB === 1'b1) out_b <= 18'd0;
        else if (OCEB === 1'b1) out_b <= rd_b;
    end
    assign {DOB17, DOB16, DOB15, DOB14, DOB13, DOB12, DOB11, DOB10, DOB9, DOB8, DOB7, DOB6, DOB5, DOB4, DOB3, DOB2, DOB1, DOB0} = REGMODE_B == "OUTREG" ? out_b : rd_b;
endmodule
`endif
/* verilator lint_on WIDTH */
/* verilator lint_on DECLFILENAME */
/* verilator lint_on UNUSEDPARAM */
/* verilator lint_on UNUSEDSIGNAL */
{% endraw %}
