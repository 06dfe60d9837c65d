{#- Macros of the unit template: the port list, a pipeline register and its delay lines. -#}
{%- macro register(c, top) -%}
{%- for line in c.lines(top) %}
{%- if !loop.first %}
{% endif %}{{ line }}
{%- endfor %}
{%- endmacro -%}
{%- macro ports(lines) -%}
{%- for line in lines %}
{{ line }}
{%- endfor %}
);
{%- endmacro -%}
