module pROMX9(CLK, CE, OCE, RESET, AD, DO);
    input         CLK, CE, OCE, RESET;
    input  [13:0] AD;
    output [35:0] DO;
    parameter READ_MODE = 1'b0;
    parameter BIT_WIDTH = 36;
    parameter RESET_MODE = "SYNC";
{%- for i in 0..64 %}
    parameter [287:0] INIT_RAM_{{ "{:02X}"|format(i) }} = 288'h0;
{%- endfor %}
