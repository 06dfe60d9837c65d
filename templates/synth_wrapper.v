// specgen timing wrapper for {{ top }}: serial I/O so the unit fits a small package.
// Every input port is loaded from a shift chain into registers, every output port is
// captured into registers and shifted out, so each path of the unit starts and ends at a
// flip-flop and nextpnr's Fmax is the unit's own. Not for use in a design.
// The consumer's ready (out_ready, m_axis_tready) is the one input the unit reads at its far
// end, beside its results; its register in the input chain sits beside the unit's first
// stage. As a consumer beside the unit would, it reaches the unit through two more free
// flip-flops (no enable, no reset), so place-and-route can put the last one next to the
// output buffer instead of routing it across the chip.
module specgen_synth_top (
    input  wire clk,
    input  wire sin,
    input  wire load,
    output wire sout
);
    reg  [{{ in_bits - 1 }}:0] in_chain;
    reg  [{{ in_bits - 1 }}:0] in_reg;
    reg  [{{ out_bits - 1 }}:0] out_reg;
    reg  [{{ out_bits - 1 }}:0] out_chain;
    wire [{{ out_bits - 1 }}:0] unit_out;
    always @(posedge clk) begin
        in_chain <= { in_chain[{{ in_bits - 2 }}:0], sin };
        if (load) in_reg <= in_chain;
        out_reg <= unit_out;
        if (load) out_chain <= out_reg;
        else      out_chain <= { out_chain[{{ out_bits - 2 }}:0], 1'b0 };
    end
    assign sout = out_chain[{{ out_bits - 1 }}];
{%- for p in inputs %}{% if p.relay %}
    reg  [{{ p.hi - p.lo }}:0] {{ p.name }}_relay, {{ p.name }}_near;
    always @(posedge clk) begin
        {{ p.name }}_relay <= in_reg[{{ p.hi }}:{{ p.lo }}];
        {{ p.name }}_near <= {{ p.name }}_relay;
    end
{%- endif %}{% endfor %}
    {{ top }} unit (
{%- if clocked %}
        .{{ clock }}(clk), .{{ reset }}(in_reg[{{ in_bits - 1 }}]),
{%- endif %}
{%- for p in inputs %}
        .{{ p.name }}({% if p.relay %}{{ p.name }}_near{% else %}in_reg[{{ p.hi }}:{{ p.lo }}]{% endif %}),
{%- endfor %}
{%- for p in outputs %}
        .{{ p.name }}(unit_out[{{ p.hi }}:{{ p.lo }}]){% if !loop.last %},{% endif %}
{%- endfor %}
    );
endmodule
