{#- Macros of the unit template: the port list, a pipeline register. -#}
{%- macro register(c) -%}
// ---- cut {{ c.index }}: pipeline register ----
reg         valid_c{{ c.index }};
{%- for s in c.signals %}
reg  [{{ s.width - 1 }}:0] {{ s.name }}_c{{ c.index }};
{%- endfor %}
always @(posedge clk) begin
    if (rst) valid_c{{ c.index }} <= 1'b0;
    else     valid_c{{ c.index }} <= {{ c.valid_source }};
end
always @(posedge clk) begin
{%- for s in c.signals %}
    {{ s.name }}_c{{ c.index }} <= {{ s.source }};
{%- endfor %}
end
{%- endmacro -%}
{%- macro ports(p, done_meaning) -%}
{%- if p.stages > 0 %}
    input  wire        clk,
    input  wire        rst,        // synchronous, active high: clears the valid pipeline
{%- endif %}
    input  wire        in_valid,
    input  wire [{{ p.cos_frac_bits }}:0] cos_g,      // UQ1.{{ p.cos_frac_bits }}: cos(gamma) = N.H; codes above 1.0 read as 1.0
    input  wire [{{ p.n_bits - 1 }}:0] n,          // unsigned specular exponent
    input  wire [{{ p.color_bits - 1 }}:0] ks_r,       // UNORM{{ p.color_bits }}: Ks * R
    input  wire [{{ p.color_bits - 1 }}:0] ks_g,       // UNORM{{ p.color_bits }}: Ks * G
    input  wire [{{ p.color_bits - 1 }}:0] ks_b,       // UNORM{{ p.color_bits }}: Ks * B
    output wire        out_valid,
    output wire [{{ p.color_bits - 1 }}:0] spec_r,     // UNORM{{ p.color_bits }}: S * ks_r
    output wire [{{ p.color_bits - 1 }}:0] spec_g,     // UNORM{{ p.color_bits }}: S * ks_g
    output wire [{{ p.color_bits - 1 }}:0] spec_b,     // UNORM{{ p.color_bits }}: S * ks_b
    output wire [{{ p.intensity_frac_bits }}:0] intensity,  // UQ1.{{ p.intensity_frac_bits }}: S
    output wire        done        // {{ done_meaning }}
);
{%- endmacro -%}
