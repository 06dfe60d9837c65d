// {{ mult }} (Gowin GW1N/GW2A {{ w }}x{{ w }} multiplier): a behavioural simulation model, written by
// specgen {{ version }} beside a unit generated with --target gowin, and used by
// `specgen synth --verify --target gowin`. For simulation only: never give it to synthesis (it
// would replace the DSP block with logic). yosys 0.70 ships {{ mult }} only as a black box
// (gowin/cells_xtra_gw1n.v) and yosys 0.23 not at all, so neither the generated RTL nor a mapped
// netlist can be simulated with yosys's models alone. Written from Gowin's DSP user guide
// (UG287, MULT18X18 and MULT9X9, one model for both): DOUT = A * B, each operand two's
// complement when its ASIGN/BSIGN is 1;
// the input registers (AREG, BREG, with the sign registers ASIGN_REG, BSIGN_REG), the pipeline
// register (PIPE_REG) and the output register (OUT_REG), each 1'b0 (bypassed) or 1'b1 (on CLK,
// enabled by CE, cleared by RESET: synchronously with MULT_RESET_MODE "SYNC", at once with
// "ASYNC"). ASEL/BSEL = 1 take the operand from the shift input SIA/SIB; SOA/SOB give the
// registered (SOA_REG) or direct operand on. The ports and parameters are the black box's.
{%- raw %}
`timescale 1ns / 1ps
// Guarded: every Gowin unit brings this model, and a design with several units reads it once.
`ifndef SPECGEN_GOWIN_{% endraw %}{{ mult }}{% raw %}_SIM
`define SPECGEN_GOWIN_{% endraw %}{{ mult }}{% raw %}_SIM
// A cell model: its ports are the primitive's, most unused here, and its file is not its name.
/* verilator lint_off UNUSEDSIGNAL */
/* verilator lint_off UNUSEDPARAM */
/* verilator lint_off DECLFILENAME */
/* verilator lint_off WIDTH */
{%- endraw %}
{% include "gowin_mult18x18_decl.v" %}
    // the operands' width
    localparam integer W = {{ w }};
{%- raw %}

    localparam ASYNC = MULT_RESET_MODE == "ASYNC";
`ifndef SYNTHESIS  // (a simulation check: `specgen prove` reads the model with SYNTHESIS)
    initial begin
        if (!(MULT_RESET_MODE == "SYNC" || MULT_RESET_MODE == "ASYNC")) begin
            $fatal(1, "%m: {% endraw %}{{ mult }}{% raw %} MULT_RESET_MODE must be \"SYNC\" or \"ASYNC\"");
        end
    end
`endif
    // a register of this block: cleared by RESET (at once when asynchronous), else loaded when CE
    wire clear_now = ASYNC & RESET;
    // the operands: the fabric's, or the shift inputs
    wire [W-1:0] a = ASEL ? SIA : A;
    wire [W-1:0] b = BSEL ? SIB : B;
    reg  [W-1:0] a_q, b_q, soa_q;
    reg          sa_q, sb_q;
    always @(posedge CLK or posedge clear_now) begin
        if (RESET) begin
            a_q <= {W{1'b0}}; b_q <= {W{1'b0}}; sa_q <= 1'b0; sb_q <= 1'b0; soa_q <= {W{1'b0}};
        end else if (CE) begin
            a_q <= a; b_q <= b; sa_q <= ASIGN; sb_q <= BSIGN; soa_q <= a;
        end
    end
    wire [W-1:0] a_in = AREG ? a_q : a;
    wire [W-1:0] b_in = BREG ? b_q : b;
    wire         sa_in = ASIGN_REG ? sa_q : ASIGN;
    wire         sb_in = BSIGN_REG ? sb_q : BSIGN;
    // the product, each operand extended by its own signedness
    wire [2*W-1:0] a_ext = {{W{sa_in & a_in[W-1]}}, a_in};
    wire [2*W-1:0] b_ext = {{W{sb_in & b_in[W-1]}}, b_in};
    wire [2*W-1:0] product = a_ext * b_ext;
    // pipeline and output registers (or none)
    reg  [2*W-1:0] pipe_q, out_q;
    wire [2*W-1:0] pipe = PIPE_REG ? pipe_q : product;
    always @(posedge CLK or posedge clear_now) begin
        if (RESET) begin
            pipe_q <= {2*W{1'b0}}; out_q <= {2*W{1'b0}};
        end else if (CE) begin
            pipe_q <= product; out_q <= pipe;
        end
    end
    assign DOUT = OUT_REG ? out_q : pipe;
    assign SOA = SOA_REG ? soa_q : a;
    assign SOB = b;
endmodule
`endif
/* verilator lint_on WIDTH */
/* verilator lint_on DECLFILENAME */
/* verilator lint_on UNUSEDPARAM */
/* verilator lint_on UNUSEDSIGNAL */
{% endraw %}
