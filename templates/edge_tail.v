{#- The outputs: a `valid` unit's assigns, or the output buffer and what it drives (its formal
    lines, `formal`, from templates/edge_formal.v; the axis packing). -#}
{%- if let Some(b) = buffer %}

// ==== the output buffer: the handshake ====
// every pixel taken has a place reserved in {{ top }}_out_buffer, so the pipeline never waits
wire {{ b.range }} out_result = {{ b.results }};
wire {{ b.range }} out_held;
`ifdef FORMAL
// formal only: what the buffer tells the unit's own assertions (see its formal block)
wire {{ b.count_range }} f_buffer_outstanding, f_buffer_results, f_buffer_rank;
wire {{ b.range }} f_buffer_at_rank;
wire [7:0]  f_buffer_progress, f_buffer_recover;
wire [{{ stages }}:0] f_buffer_takes;
`endif
{{ top }}_out_buffer #(.WIDTH({{ b.width }}), .DEPTH_LOG2({{ b.depth_log2 }}), .TAPS({{ b.taps }}), .PLACES({{ b.places }}), .LATENCY({{ stages }})) out_buffer (
    .clk(clk), .rst(rst), .in_valid({{ b.offer }}), .in_ready(in_ready), .take(in_take),
    .result_valid({{ last_valid }}), .result(out_result),
    .out_valid(out_valid), .out_ready({{ b.accept }}), .out(out_held)
`ifdef FORMAL
    , .f_outstanding(f_buffer_outstanding), .f_results(f_buffer_results), .f_rank(f_buffer_rank),
    .f_at_rank(f_buffer_at_rank), .f_progress(f_buffer_progress), .f_recover(f_buffer_recover), .f_takes(f_buffer_takes)
`endif
);
{%- if static_colour %}
{#- idle from a flip-flop: a thermometer of the pixels inside (0..=places), bit k set while k
    or more are; two LUT levels from the handshake, no carry chain and no OR over the pipeline:
    first each bit as it would be after the take alone (in_take ? bit k-1 : bit k, kept), then
    the delivery picks it or its neighbour above (a delivery moves every bit down one) #}

// ---- idle: a thermometer of the pixels inside (taken, not yet delivered) ----
reg  [{{ b.places }}:1] inside_at_least;   // bit k: k or more pixels inside
wire [{{ b.places + 1 }}:0] inside_level = {1'b0, inside_at_least, 1'b1};   // with its two ends
// bit k after the take alone (k = 1 ..= places + 1): one LUT of in_take and two bits
// (AND-OR, not ?: a hold would become a flip-flop enable that the handshake and rst reach)
(* keep *) wire [{{ b.places + 1 }}:1] inside_taken;
assign inside_taken = ({ {{- b.places + 1 }}{in_take}} & inside_level[{{ b.places }}:0]) | ({ {{- b.places + 1 }}{!in_take}} & inside_level[{{ b.places + 1 }}:1]);
wire        inside_given = out_valid && {{ b.accept }};   // a delivery
reg  idle_q;   // none inside: bit 1 clear, a flip-flop of its own
always @(posedge clk) begin
    if (rst) begin
        inside_at_least <= {{ b.places }}'h0;
        idle_q          <= 1'b1;
    end else begin
        // a delivery moves every bit down one
        inside_at_least <= ({ {{- b.places }}{inside_given}} & inside_taken[{{ b.places + 1 }}:2]) | ({ {{- b.places }}{!inside_given}} & inside_taken[{{ b.places }}:1]);
        idle_q          <= !((inside_given & inside_taken[2]) | (!inside_given & inside_taken[1]));
    end
end
assign idle      = idle_q;   // no pixel in the pipeline or the buffer
{%- endif %}
assign {{ b.ports }} = out_held;
{%- for line in formal %}
{{ line }}
{%- endfor %}
{%- if let Some(tdata) = b.tdata %}
assign m_axis_tdata = {{ tdata }};
{%- endif %}
{%- if let Some((lhs, above)) = b.carried %}
assign {{ lhs }} = out_tag;
{%- if let Some(bits) = above %}   // tlast above the tag ({{ bits }} bits){% endif %}
{%- endif %}
{%- else %}

assign out_valid = {{ last_valid }};
{%- for (port, source) in outputs %}
assign {{ "{:<9}"|format(port) }} = {{ source }};
{%- endfor %}
{%- if let Some(t) = tag_out %}
assign out_tag   = {{ t }};
{%- endif %}
{%- if static_colour && stages == 0 %}
assign idle      = 1'b1;   // no pipeline: never a pixel inside
{%- else if static_colour %}
{#- registered, from what valid_line holds after this edge: idle leaves the unit from a
    flip-flop, not through an OR of the whole valid pipeline. After the edge valid_line holds
    in_valid and its bits 0 ..= depth - 2; those bits are valid_seen, one flag for each four,
    registered one edge ahead too (each a LUT of four bits, as they shift in), so idle_q's input
    is an OR of in_valid and the flags: two LUT levels at any depth (an OR of the whole pipeline
    is three from 17 stages on) #}
reg  idle_q;   // no pixel in the pipeline: ~|valid_line, one edge ahead
{%- if let Some((range, top_bit, groups, next)) = valid_seen %}
reg  {{ range }} valid_seen;   // bit j: a pixel in valid_line[4j+3:4j] (bits 0..={{ top_bit }}), one edge ahead
always @(posedge clk) begin
    if (rst) valid_seen <= {{ groups }}'h0;
    else     valid_seen <= {{ next }};
end
always @(posedge clk) idle_q <= rst | ~(in_valid | (|valid_seen));
{%- else %}
always @(posedge clk) idle_q <= rst | ~(in_valid);
{%- endif %}
assign idle      = idle_q;
{%- endif %}
{%- endif %}
