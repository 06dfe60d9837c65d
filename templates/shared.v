{#- Macros shared by the unit templates: the port list, a pipeline cut point, the outputs. -#}
{%- macro cut(c) -%}
// ---- cut {{ c.index }}: {% if c.registered %}pipeline register{% else %}combinational pass-through{% endif %} ----
{%- if c.registered %}
reg         valid_c{{ c.index }};
{%- for s in c.signals %}
reg  [{{ s.width - 1 }}:0] {{ s.name }}_c{{ c.index }};
{%- endfor %}
always @(posedge clk) begin
    if (rst) valid_c{{ c.index }} <= 1'b0;
    else     valid_c{{ c.index }} <= valid_c{{ c.index - 1 }};
end
always @(posedge clk) begin
{%- for s in c.signals %}
    {{ s.name }}_c{{ c.index }} <= {{ s.source }};
{%- endfor %}
end
{%- else %}
wire        valid_c{{ c.index }} = valid_c{{ c.index - 1 }};
{%- for s in c.signals %}
wire [{{ s.width - 1 }}:0] {{ s.name }}_c{{ c.index }} = {{ s.source }};
{%- endfor %}
{%- endif %}
{%- endmacro -%}
{%- macro outputs(last) -%}
assign out_valid = valid_c{{ last }};
assign spec_r    = spec_r_c{{ last }};
assign spec_g    = spec_g_c{{ last }};
assign spec_b    = spec_b_c{{ last }};
assign intensity = intensity_c{{ last }};
assign done      = done_c{{ last }};
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
