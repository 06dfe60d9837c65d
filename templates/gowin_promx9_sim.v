// pROMX9 (Gowin GW1N/GW2A 18-kbit block RAM as a ROM, x9 widths): a behavioural simulation
// model, written by specgen {{ version }} beside a unit generated with --target gowin whose table
// is in block RAM, and used by `specgen synth --verify --target gowin`. For simulation only:
// never give it to synthesis. yosys 0.70 ships pROMX9 only as a black box
// (gowin/cells_xtra_gw1n.v) and yosys 0.23 not at all. Written from Gowin's BSRAM user guide
// (UG285, pROMX9): the contents are INIT_RAM_00..3F, 288 bits each, read as one array of 9-bit
// units (INIT_RAM_(i/32) bits [(i%32)*9 +: 9] is unit i, as yosys's gowin/brams_map.v lays them
// out); BIT_WIDTH 9, 18 or 36 reads 1, 2 or 4 units at the address AD[13:3], AD[13:4] or
// AD[13:5] (the low address bits select bytes of a write, which a ROM has none of). The read is
// synchronous (the address register on CLK, enabled by CE); READ_MODE 1'b1 adds the output
// register (enabled by OCE), 1'b0 bypasses it. RESET clears the output (synchronously with
// RESET_MODE "SYNC", at once with "ASYNC"). Ports and parameters are the black box's.
{%- raw %}
`timescale 1ns / 1ps
// Guarded: every Gowin unit with a table in block RAM brings this model, and a design with
// several units reads it once.
`ifndef SPECGEN_GOWIN_PROMX9_SIM
`define SPECGEN_GOWIN_PROMX9_SIM
// A cell model: its ports are the primitive's, most unused here, and its file is not its name.
/* verilator lint_off UNUSEDSIGNAL */
/* verilator lint_off UNUSEDPARAM */
/* verilator lint_off DECLFILENAME */
/* verilator lint_off WIDTH */
{%- endraw %}
{% include "gowin_promx9_decl.v" %}
{%- raw %}

    localparam ASYNC = RESET_MODE == "ASYNC";
`ifndef SYNTHESIS  // (a simulation check: `specgen prove` reads the model with SYNTHESIS)
    initial begin
        if (!(BIT_WIDTH == 9 || BIT_WIDTH == 18 || BIT_WIDTH == 36) || !(RESET_MODE == "SYNC" || RESET_MODE == "ASYNC")) begin
            $fatal(1, "%m: pROMX9 BIT_WIDTH must be 9, 18 or 36 and RESET_MODE \"SYNC\" or \"ASYNC\"");
        end
    end
`endif
    // the contents: 64 rows of 288 bits, 2048 units of 9 bits
    reg [287:0] mem [0:63];
    initial begin
        mem[0] = INIT_RAM_00;
        mem[1] = INIT_RAM_01;
        mem[2] = INIT_RAM_02;
        mem[3] = INIT_RAM_03;
        mem[4] = INIT_RAM_04;
        mem[5] = INIT_RAM_05;
        mem[6] = INIT_RAM_06;
        mem[7] = INIT_RAM_07;
        mem[8] = INIT_RAM_08;
        mem[9] = INIT_RAM_09;
        mem[10] = INIT_RAM_0A;
        mem[11] = INIT_RAM_0B;
        mem[12] = INIT_RAM_0C;
        mem[13] = INIT_RAM_0D;
        mem[14] = INIT_RAM_0E;
        mem[15] = INIT_RAM_0F;
        mem[16] = INIT_RAM_10;
        mem[17] = INIT_RAM_11;
        mem[18] = INIT_RAM_12;
        mem[19] = INIT_RAM_13;
        mem[20] = INIT_RAM_14;
        mem[21] = INIT_RAM_15;
        mem[22] = INIT_RAM_16;
        mem[23] = INIT_RAM_17;
        mem[24] = INIT_RAM_18;
        mem[25] = INIT_RAM_19;
        mem[26] = INIT_RAM_1A;
        mem[27] = INIT_RAM_1B;
        mem[28] = INIT_RAM_1C;
        mem[29] = INIT_RAM_1D;
        mem[30] = INIT_RAM_1E;
        mem[31] = INIT_RAM_1F;
        mem[32] = INIT_RAM_20;
        mem[33] = INIT_RAM_21;
        mem[34] = INIT_RAM_22;
        mem[35] = INIT_RAM_23;
        mem[36] = INIT_RAM_24;
        mem[37] = INIT_RAM_25;
        mem[38] = INIT_RAM_26;
        mem[39] = INIT_RAM_27;
        mem[40] = INIT_RAM_28;
        mem[41] = INIT_RAM_29;
        mem[42] = INIT_RAM_2A;
        mem[43] = INIT_RAM_2B;
        mem[44] = INIT_RAM_2C;
        mem[45] = INIT_RAM_2D;
        mem[46] = INIT_RAM_2E;
        mem[47] = INIT_RAM_2F;
        mem[48] = INIT_RAM_30;
        mem[49] = INIT_RAM_31;
        mem[50] = INIT_RAM_32;
        mem[51] = INIT_RAM_33;
        mem[52] = INIT_RAM_34;
        mem[53] = INIT_RAM_35;
        mem[54] = INIT_RAM_36;
        mem[55] = INIT_RAM_37;
        mem[56] = INIT_RAM_38;
        mem[57] = INIT_RAM_39;
        mem[58] = INIT_RAM_3A;
        mem[59] = INIT_RAM_3B;
        mem[60] = INIT_RAM_3C;
        mem[61] = INIT_RAM_3D;
        mem[62] = INIT_RAM_3E;
        mem[63] = INIT_RAM_3F;
    end
    // unit i of the array
    function [8:0] unit_at;
        input [10:0] i;
        reg [287:0] row;
        begin
            row = mem[i[10:5]];
            unit_at = row[i[4:0] * 9 +: 9];
        end
    endfunction
    // the word at an address, in the low BIT_WIDTH bits
    function [35:0] word_at;
        input [13:0] ad;
        begin
            if (BIT_WIDTH == 9) word_at = {27'd0, unit_at(ad[13:3])};
            else if (BIT_WIDTH == 18) word_at = {18'd0, unit_at({ad[13:4], 1'b1}), unit_at({ad[13:4], 1'b0})};
            else word_at = {unit_at({ad[13:5], 2'd3}), unit_at({ad[13:5], 2'd2}), unit_at({ad[13:5], 2'd1}), unit_at({ad[13:5], 2'd0})};
        end
    endfunction
    wire clear_now = ASYNC & RESET;
    reg [35:0] read_q, out_q;
    // the synchronous read (the address register), then the output register
    always @(posedge CLK or posedge clear_now) begin
        if (RESET) begin
            read_q <= 36'd0;
        end else if (CE) begin
            read_q <= word_at(AD);
        end
    end
    always @(posedge CLK or posedge clear_now) begin
        if (RESET) begin
            out_q <= 36'd0;
        end else if (OCE) begin
            out_q <= read_q;
        end
    end
    assign DO = READ_MODE ? out_q : read_q;
endmodule
`endif
/* verilator lint_on WIDTH */
/* verilator lint_on DECLFILENAME */
/* verilator lint_on UNUSEDPARAM */
/* verilator lint_on UNUSEDSIGNAL */
{% endraw %}
