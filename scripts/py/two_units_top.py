"""A step of scripts/bench_two_units.sh (its arguments as there: sys.argv[1:])."""
import json, sys
work, kind, units = sys.argv[1], sys.argv[2], [u.split(":") for u in sys.argv[3:]]
ins, outs, inst = 0, 0, []
for top, *_ in units:
    ports = json.load(open(f"{work}/{top}/{top}.json"))["ports"]
    conn = []
    for p in ports:
        n, w = p["name"], p["width"]
        if n == "clk":
            conn.append(".clk(clk)")
        elif p["direction"] == "input":
            conn.append(f".{n}(in_reg[{ins + w - 1}:{ins}])"); ins += w
        else:
            conn.append(f".{n}(unit_out[{outs + w - 1}:{outs}])"); outs += w
    inst.append(f"    {top} u_{top} ({', '.join(conn)});")
names = " and ".join(f"`{u[0]}`" for u in units)
if kind == "serial":
    # (the units read the input chain's flip-flops and the output chain loads their outputs:
    # no holding registers between, 188 flip-flops fewer, which the device nearly full needs;
    # a unit's inputs changing while the chain shifts changes no path)
    print(f"""// two specgen units in one device, serial I/O (scripts/bench_two_units.sh); not for a design
module pair_top (input wire clk, input wire sin, input wire load, output wire sout);
    reg  [{ins - 1}:0] in_reg;
    reg  [{outs - 1}:0] out_chain;
    wire [{outs - 1}:0] unit_out;
    always @(posedge clk) begin
        in_reg <= {{in_reg[{ins - 2}:0], sin}};
        if (load) out_chain <= unit_out;
        else      out_chain <= {{out_chain[{outs - 2}:0], 1'b0}};
    end
    assign sout = out_chain[{outs - 1}];
{chr(10).join(inst)}
endmodule""")
else:
    # a user's own top: each unit fed by plain registers (here from a shift register the pins
    # feed, standing for the user's pipeline) and read by plain registers (here their parity,
    # folded four bits a register level, to a pin: a LUT a level, so the top adds no long path)
    decls, folds, width, src, level = [], [], outs, "out_reg", 0
    while width > 1:
        groups = (width + 3) // 4
        pad = 4 * groups - width
        decls.append(f"    wire [{4 * groups - 1}:0] fold{level}_in = " + (f"{{{pad}'d0, {src}}};" if pad else f"{src};"))
        decls.append(f"    reg  [{groups - 1}:0] fold{level} = {groups}'d0;")
        folds.append(f"        for (i = 0; i < {groups}; i = i + 1) fold{level}[i] <= ^fold{level}_in[4 * i +: 4];")
        width, src, level = groups, f"fold{level}", level + 1
    print(f"""// Two specgen units in a top of one's own (written by scripts/bench_two_units.sh):
// {names} fed by plain registers and read by plain registers, no serial wrapper. The registers stand for
// the user's pipeline: `src` is a shift register the pins `din` feed; the outputs' parity is
// folded four bits a register level to the pin `dout` (so that nothing is optimized away).
`timescale 1ns / 1ps
`default_nettype none
module pair_plain_top (
    input  wire       clk,
    input  wire [3:0] din,
    output wire       dout
);
    reg  [{ins - 1}:0] src = {ins}'d0;      // the user's data, shifted in from the pins
    reg  [{ins - 1}:0] in_reg = {ins}'d0;   // every unit input from a plain register
    wire [{outs - 1}:0] unit_out;
    reg  [{outs - 1}:0] out_reg = {outs}'d0; // every unit output into a plain register
{chr(10).join(decls)}
    integer i;
    always @(posedge clk) begin
        src <= {{src[{ins - 5}:0], din}};
        in_reg <= src;
        out_reg <= unit_out;
{chr(10).join(folds)}
    end
    assign dout = {src}[0];
{chr(10).join(inst)}
endmodule
`default_nettype wire""")
