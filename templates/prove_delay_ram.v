// {{ name }}: the contract of {{ top }}_delay_ram at WIDTH = {{ width }}, CUTS = {{ cuts }}, generated
// by specgen {{ version }} for `specgen prove --pipelining`. Do not edit.
// d is free at every edge; the memory and its registers hold anything at power-up (the write
// address starts at its first value). The harness follows one word, any one (written at the
// edge where `follow` is first high), and asserts that q is that word exactly CUTS - 1 edges
// after it was written: for every word, q is d of CUTS edges before from the CUTS-th edge on,
// what CUTS flip-flops in a row hold.
`default_nettype none
module {{ name }} (
    input  wire                clk,
    input  wire                follow,
    input  wire [{{ width - 1 }}:0] d
);
    localparam integer CUTS = {{ cuts }};
    wire [{{ width - 1 }}:0] q;
    // the word followed, and the edges since it was written (0: none yet; counted to CUTS + 1)
    reg         following = 1'b0;
    reg  [15:0] age;
    reg  [{{ width - 1 }}:0] value;
    always @(posedge clk) begin
        if (!following && follow) begin
            following <= 1'b1;
            age <= 16'd1;
            value <= d;
        end else if (following && age != CUTS + 1) begin
            age <= age + 16'd1;
        end
    end
    wire [15:0] f_age = following ? age : 16'd0;
    // the module's lemmas read the word followed and its age
{%- if lemmas %}
    {{ top }}_delay_ram #(.WIDTH({{ width }}), .CUTS(CUTS)) line (.clk(clk), .d(d), .q(q), .f_age(f_age), .f_value(value));
{%- else %}
    // (the module has no lemma ports: the contract alone, which induction may not close)
    {{ top }}_delay_ram #(.WIDTH({{ width }}), .CUTS(CUTS)) line (.clk(clk), .d(d), .q(q));
    wire unused_age = ^f_age;
{%- endif %}
    always @* if (following) assert (age >= 16'd1 && age <= CUTS + 1);
    // the contract
    always @* if (following && age == CUTS) assert (q == value);
endmodule
