// specgen co-simulation bench for Icarus Verilog (-g2005): generic over every configuration.
//
// It drives specgen_cosim_top, the adapter specgen writes for each unit (one set of port names
// for every interface mode). Defines (passed with -D by specgen cosim): COS_W, N_W, B_W, I_W
// (port widths). Plusargs +vec_in=FILE +vec_out=FILE.
// vec_in holds one cycle a line, in hex: "in_valid rst cos_g n ks_r ks_g ks_b out_ready load tag",
// load's bit 0 ks_load, its bit 1 the clock enable low.
// vec_out gets one line a cycle, in hex: "out_valid done intensity spec_r spec_g spec_b in_ready idle tag",
// sampled after the inputs settle and before the clock's rising edge (as the C++ harness).
`timescale 1ns/1ps
module specgen_icarus_bench;
    reg             in_valid, rst, clk, out_ready, ks_load, clk_en;
    reg  [`COS_W-1:0] cos_g;
    reg  [`N_W-1:0]   n;
    reg  [`B_W-1:0]   ks_r, ks_g, ks_b;
    reg  [63:0]     in_tag;
    wire            out_valid, done, in_ready, idle;
    wire [`B_W-1:0]   spec_r, spec_g, spec_b;
    wire [`I_W-1:0]   intensity;
    wire [63:0]     out_tag;
    integer         fin, fout, got;
    reg  [31:0]     v_valid, v_rst, v_cos, v_n, v_r, v_g, v_b, v_ready, v_load;
    reg  [63:0]     v_tag;
    reg  [8*1024-1:0] vec_in, vec_out;

    specgen_cosim_top dut (
        .clk(clk), .rst(rst), .in_valid(in_valid), .out_ready(out_ready), .ks_load(ks_load), .clk_en(clk_en),
        .cos_g(cos_g), .n(n), .ks_r(ks_r), .ks_g(ks_g), .ks_b(ks_b), .in_tag(in_tag),
        .in_ready(in_ready), .out_valid(out_valid), .spec_r(spec_r), .spec_g(spec_g), .spec_b(spec_b),
        .intensity(intensity), .done(done), .out_tag(out_tag), .idle(idle));

    initial begin
        clk = 1'b0;
        if (!$value$plusargs("vec_in=%s", vec_in) || !$value$plusargs("vec_out=%s", vec_out)) begin
            $display("specgen bench: +vec_in=FILE and +vec_out=FILE are required");
            $finish;
        end
        fin = $fopen(vec_in, "r");
        fout = $fopen(vec_out, "w");
        if (fin == 0 || fout == 0) begin
            $display("specgen bench: cannot open vector files");
            $finish;
        end
        got = $fscanf(fin, "%h %h %h %h %h %h %h %h %h %h\n", v_valid, v_rst, v_cos, v_n, v_r, v_g, v_b, v_ready, v_load, v_tag);
        while (got == 10) begin
            in_valid = v_valid[0];
            rst = v_rst[0];
            cos_g = v_cos[`COS_W-1:0];
            n = v_n[`N_W-1:0];
            ks_r = v_r[`B_W-1:0];
            ks_g = v_g[`B_W-1:0];
            ks_b = v_b[`B_W-1:0];
            out_ready = v_ready[0];
            ks_load = v_load[0];
            clk_en = !v_load[1];
            in_tag = v_tag;
            clk = 1'b0;
            #5;
            $fwrite(fout, "%h %h %h %h %h %h %h %h %h\n", out_valid, done, intensity, spec_r, spec_g, spec_b, in_ready, idle, out_tag);
            clk = 1'b1;
            #5;
            got = $fscanf(fin, "%h %h %h %h %h %h %h %h %h %h\n", v_valid, v_rst, v_cos, v_n, v_r, v_g, v_b, v_ready, v_load, v_tag);
        end
        $fclose(fout);
        $finish;
    end
endmodule
