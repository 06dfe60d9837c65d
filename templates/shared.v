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
{%- macro ports(lines) -%}
{%- for line in lines %}
{{ line }}
{%- endfor %}
);
{%- endmacro -%}
