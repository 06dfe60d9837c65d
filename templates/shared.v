{#- Macros of the unit template: the port list, a pipeline register and its delay lines. -#}
{%- macro register(c) -%}
{%- for d in c.declarations() %}
{{ d }}
{%- endfor %}
{%- for l in c.lines %}
reg  [{{ l.width * l.depth - 1 }}:0] {{ l.name }}_line;   // {{ l.name }} through cuts {{ l.first }}..{{ l.last }}, {{ l.width }} bits a cut
{%- for (tap, hi, lo) in l.taps %}
wire {% if l.width == 1 %}      {% else %}[{{ l.width - 1 }}:0]{% endif %} {{ tap }} = {{ l.name }}_line[{% if hi == lo %}{{ hi }}{% else %}{{ hi }}:{{ lo }}{% endif %}];
{%- endfor %}
{%- endfor %}
always @(posedge clk) begin   // cut {{ c.index }}: the registers after step {{ c.index }}
{%- for s in c.signals %}
    {{ s.name }}_c{{ c.index }} <= {{ s.source }};
{%- endfor %}
{%- for l in c.lines %}
    {{ l.name }}_line <= {{ l.shift }};
{%- endfor %}
end
{%- endmacro -%}
{%- macro ports(lines) -%}
{%- for line in lines %}
{{ line }}
{%- endfor %}
);
{%- endmacro -%}
