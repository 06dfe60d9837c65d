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
