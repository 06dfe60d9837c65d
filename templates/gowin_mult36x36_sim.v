// MULT36X36 (Gowin GW1N/GW2A 36x36 multiplier): a simulation model of the one setting yosys
// infers it with, written by specgen {{ version }} for `specgen synth --verify --target gowin`.
// yosys 0.70's synth_gowin maps a product wider than 18x18 that no cut surrounds to a MULT36X36
// (gowin/dsp_map.v: every register parameter left at its default, 1'b0) and ships the
// primitive only as a black box. Modelled here: DOUT = A * B, each operand two's complement when
// its ASIGN/BSIGN is 1, without registers. Any register parameter set (AREG, BREG, OUT0_REG,
// OUT1_REG, PIPE_REG, ASIGN_REG, BSIGN_REG) stops the simulation: their timing is not modelled.
// For simulation only: never give it to synthesis.
{%- raw %}
`timescale 1ns / 1ps
`ifndef SPECGEN_GOWIN_MULT36X36_SIM
`define SPECGEN_GOWIN_MULT36X36_SIM
// A cell model: its ports are the primitive's, the clock ones unused here, and its file is not its name.
/* verilator lint_off UNUSEDSIGNAL */
/* verilator lint_off UNUSEDPARAM */
/* verilator lint_off DECLFILENAME */
module MULT36X36(A, B, ASIGN, BSIGN, CE, CLK, RESET, DOUT);
    input  [35:0] A;
    input  [35:0] B;
    input         ASIGN, BSIGN;
    input         CE;
    input         CLK;
    input         RESET;
    output [71:0] DOUT;
    parameter AREG = 1'b0;
    parameter BREG = 1'b0;
    parameter OUT0_REG = 1'b0;
    parameter OUT1_REG = 1'b0;
    parameter PIPE_REG = 1'b0;
    parameter ASIGN_REG = 1'b0;
    parameter BSIGN_REG = 1'b0;
    parameter MULT_RESET_MODE = "SYNC";
`ifndef SYNTHESIS
    initial begin
        if (AREG != 0 || BREG != 0 || OUT0_REG != 0 || OUT1_REG != 0 || PIPE_REG != 0 || ASIGN_REG != 0 || BSIGN_REG != 0) begin
            $fatal(1, "%m: MULT36X36 with a register: this model has only the combinational setting yosys infers");
        end
    end
`endif
    // the product, each operand extended by its own signedness
    wire [71:0] a_ext = {{36{ASIGN & A[35]}}, A};
    wire [71:0] b_ext = {{36{BSIGN & B[35]}}, B};
    assign DOUT = a_ext * b_ext;
endmodule
`endif
/* verilator lint_on DECLFILENAME */
/* verilator lint_on UNUSEDPARAM */
/* verilator lint_on UNUSEDSIGNAL */
{% endraw %}
