{#- The declarations after the port list: the reset active high inside, the axis aliases, the
    enabled handshake, the take, the material registers. `range(w)` is a declaration's `[w-1:0]`
    padded to 6 (blank for one bit). -#}
{%- if reset_from_low %}
wire        rst = ~rst_n;   // active high inside
{%- endif %}
{%- if let Some(a) = axis %}
// ---- AXI4-Stream names: the logic below uses the plain ones ----
wire        clk       = aclk;
wire        rst       = {{ a.reset }};   // active high inside
wire        in_valid  = s_axis_tvalid{{ a.gate }}
wire        out_ready = m_axis_tready{{ a.gate }}
wire        in_ready, out_valid;
{%- for f in a.fields %}
wire {{ f.range }} {{ "{:<9}"|format(f.name) }} = s_axis_tdata[{{ f.hi }}:{{ f.lo }}];
{%- endfor %}
{%- if let Some(source) = a.tag_source %}
wire {{ tag_range }} in_tag    = {{ source }};
{%- endif %}
wire {{ colour_range }} spec_r, spec_g, spec_b;
wire {{ a.intensity_range }} intensity;
wire        done;
{%- if a.tag_source.is_some() %}
wire {{ tag_range }} out_tag;
{%- endif %}
assign s_axis_tready = in_ready;
assign m_axis_tvalid = out_valid;
{%- endif %}
{%- if let Some((offer, accept, en)) = enabled_ready %}
wire        {{ offer }}  = in_valid & {{ en }};    // a transfer only at an enabled edge
wire        {{ accept }} = out_ready & {{ en }};
{%- endif %}
{%- if handshake %}
wire        in_take;   // in_valid && in_ready: the pipeline takes a pixel ({{ top }}_out_buffer)
{%- endif %}
{%- if let Some(load) = material_load %}
{#- kept: yosys 0.70 takes a register a multiplier reads into the SB_MAC16 as its input register,
    ks_load its hold, a 6.5 ns route into the DSP tile (blinn static 94.8 MHz) #}

// ---- the material registers: ks_load takes ks_r/g/b; every step reads them ----
(* keep *) reg  {{ colour_range }} ks_r_material, ks_g_material, ks_b_material;   // UNORM{{ colour_bits }}
always @(posedge clk) if ({{ load }}) {ks_r_material, ks_g_material, ks_b_material} <= {ks_r, ks_g, ks_b};
{%- endif %}
