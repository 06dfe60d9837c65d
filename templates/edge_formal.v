{#- The unit's own formal block (read only with `yosys -formal`, as `specgen prove` does; see
    templates/out_buffer.v for the buffer's): with a tag, the tag entering the buffer with a
    result is in_tag of the pixel `depth` edges before; with material registers, idle is high
    exactly while no pixel is inside. Each is an assertion `prove` proves, with the invariants
    that make it inductive within a few edges. Then the lemmas (under SPECGEN_LEMMAS, with the
    port f_ports): the port checker's state, written from the manifest apart from the unit, tied
    to the unit's own, so the checker's stream rules close by induction. The pixels inside are
    the buffer's count; a result owed has waited no longer than the unit's progress toward one
    (f_progress of the buffer); the pixel followed is, by its age, at its stage of the pipeline
    (its tag there, the pixels inside less those at or behind its stage ahead of it) or in the
    buffer at its rank with its tag. A false lemma fails the proof; none can pass a unit that
    breaks a rule. With `prove --datapath`, the followed pixel's result in the buffer is the one
    the `valid` twin computed for it. #}

`ifdef FORMAL
// ==== formal (read with yosys -formal, as `specgen prove` does; synthesis and simulation never read it) ====
reg  f_started = 1'b0;   // the first edge (a reset: the buffer's assumption) has passed
always @(posedge clk) f_started <= 1'b1;
{%- if let Some((last, shift)) = tag %}
// in_tag of the last {{ depth }} edges (word j: j + 1 edges before), and how many edges have passed (bit j: more than j)
reg  [{{ depth * tw - 1 }}:0] f_tags;
reg  [{{ depth - 1 }}:0] f_age = {{ depth }}'h0;
{%- if depth == 1 %}
always @(posedge clk) begin f_tags <= in_tag; f_age <= 1'b1; end
{%- else %}
always @(posedge clk) begin f_tags <= {f_tags[{{ (depth - 1) * tw - 1 }}:0], in_tag}; f_age <= {f_age[{{ depth - 2 }}:0], 1'b1}; end
{%- endif %}
always @(*) if (f_started) begin
    // the tag that enters the buffer with a result is its pixel's: in_tag {{ depth }} edges before
    if (valid_line[{{ depth - 1 }}]) assert({{ last }} == f_tags[{{ depth * tw - 1 }}:{{ (depth - 1) * tw }}]);
    // (a pixel in the pipeline was taken after power-up)
    assert((valid_line & ~f_age) == 0);
{%- if shift %}
    // the line is a shift register: each word is in_tag j + 1 edges before, once that many have passed
{%- for j in 0..depth %}
    if (f_age[{{ j }}]) assert(tag_line[{{ j * tw }} +: {{ tw }}] == f_tags[{{ j * tw }} +: {{ tw }}]);
{%- endfor %}
{%- endif %}
end
{%- endif %}
{%- if let Some(p) = places %}
integer f_k, f_count;
always @(*) begin
    f_count = 0;
    for (f_k = 1; f_k <= {{ p }}; f_k = f_k + 1) f_count = f_count + inside_at_least[f_k];
    if (f_started) begin
        // idle is high exactly while no pixel is inside (the buffer counts them)
        assert(idle_q == (f_buffer_outstanding == 0));
        // the thermometer is one, and counts them
        for (f_k = 1; f_k < {{ p }}; f_k = f_k + 1) if (inside_at_least[f_k + 1]) assert(inside_at_least[f_k]);
        assert(f_count == f_buffer_outstanding);
    end
end
{%- endif %}
`ifdef SPECGEN_LEMMAS
// ---- lemmas (`specgen prove` at the ports): the port checker's state, f_ports, tied to the unit's ----
{%- for (name, range, select, what) in fields %}
wire {{ range }} f_ports_{{ "{:<9}"|format(name) }} = {{ select }};   // {{ what }}
{%- endfor %}
assign f_buffer_rank = f_ports_rank;
{%- if depth > 0 %}
integer f_p, f_behind;
{%- if tw > 0 %}
reg  {{ tag_range }} f_tag_at_age;   // in_tag of the edge the followed pixel was taken
{%- endif %}
{%- endif %}
always @(*) begin
{%- if depth > 0 %}
    f_behind = 0;   // pixels in the pipeline at the followed one's stage or behind it
    for (f_p = 0; f_p < {{ depth }}; f_p = f_p + 1) if (f_p <= f_ports_age) f_behind = f_behind + valid_line[f_p];
{%- if tw > 0 %}
{#- (a constant part-select in a loop: yosys 0.23 reads `f_tags[f_ports_age * T +: T]` wrongly) #}
    f_tag_at_age = {{ tw }}'h0;
    for (f_p = 0; f_p < {{ depth }}; f_p = f_p + 1) if (f_p == f_ports_age) f_tag_at_age = f_tags[f_p * {{ tw }} +: {{ tw }}];
{%- endif %}
{%- endif %}
    if (f_started) begin
{%- if depth > 0 %}
        // the pipeline's valid bits are the pixels the buffer saw taken
        assert(valid_line == f_buffer_takes[{{ depth - 1 }}:0]);
{%- endif %}
        // the checker counts the pixels inside as the buffer does
        assert(f_ports_inside == f_buffer_outstanding);
        // a result owed has waited no longer than the unit's progress toward delivering one
        assert(f_ports_owed <= f_buffer_progress);
        // and one owed and not shown: out_valid never waits for out_ready
        assert(f_ports_waiting <= f_buffer_progress);
        // in_ready low: the edges it has been low to a ready consumer and those it stays low
        // are {{ recover }} at most (the checker's bound: latency + places + 4)
        if (!in_ready) assert(f_ports_refused + f_buffer_recover <= {{ recover }});
{%- if depth > 0 %}
        if (f_ports_following && f_ports_age < {{ depth }}) begin
            // in the pipeline, at the stage of its age: a pixel there, its tag with it, those inside
            // less those at its stage or behind it ahead of it
            assert(valid_line[f_ports_age]);
{%- if tw > 0 %}
            assert(f_tag_at_age == f_ports_word);
{%- endif %}
            assert(f_ports_rank == f_ports_inside - f_behind);
        end
{%- endif %}
        if (f_ports_following && f_ports_age >= {{ depth }}) begin
            // in the buffer, at its rank, with its tag
            assert(f_ports_rank < f_buffer_results);
{%- if tw > 0 %}
            assert(f_buffer_at_rank[{{ width - 1 }}:{{ width - tw }}] == f_ports_word);
{%- endif %}
            // (prove --datapath) with the result the twin computed for it
            if (f_ports_check) assert({{ payload }} == f_ports_expected);
        end
    end
end
`else
assign f_buffer_rank = 0;
`endif
`endif
