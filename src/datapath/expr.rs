//! What a wire computes, as data: its kind ([`Kind`]: a bit select, a sum, a product, a
//! table, other logic) and the signals it reads, each recorded when the builder made the
//! operand ([`Builder::bits`](super::Builder::bits) and the helpers over it), never found again
//! by reading the Verilog text. The text is only how a step is rendered.

use std::fmt;

/// What a wire of a step computes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// Bits selected and concatenated (and constants): no logic, no delay. A register read
    /// through such wires only is still read whole (`Datapath::read_by_block`).
    Select,
    /// A sum or difference: a carry chain, or a part of a carry-select or carry-save add.
    Sum,
    /// A product the family's synthesis maps (`a * b`, perhaps `+ addend`): its operands'
    /// significant bits (`Builder::mul`). A product in the fabric is its partial products and
    /// sums instead.
    Product(u32, u32),
    /// A table written as logic (a case over its address, in LUTs).
    Table,
    /// Any other logic: compares, selects, gates, reductions.
    Logic,
}

/// An expression of a step: its Verilog text and the names it reads (`x_c3`, `x_s4`, a port,
/// a held register), in the order first read, each once.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Expr {
    pub(crate) text: String,
    pub(crate) reads: Vec<String>,
}

impl Expr {
    /// A reference to one name (`name` is what the text reads).
    pub(crate) fn read(name: String, text: String) -> Expr {
        Expr {
            text,
            reads: vec![name],
        }
    }

    /// A constant, or any text that reads no signal.
    pub(crate) fn constant(text: impl Into<String>) -> Expr {
        Expr {
            text: text.into(),
            reads: Vec::new(),
        }
    }

    /// Whether the text is empty (an addend of constant zeros).
    pub(crate) fn is_empty(&self) -> bool {
        self.text.is_empty()
    }

    /// The complement of a one-bit expression: `~x` for a name or a bit of one, `x` for `~x`,
    /// `~(...)` otherwise.
    pub(crate) fn not(&self) -> Expr {
        let simple = |t: &str| {
            !t.is_empty()
                && t.chars()
                    .all(|c| c.is_ascii_alphanumeric() || "_[]:".contains(c))
        };
        let text = match self.text.strip_prefix('~') {
            Some(t) if simple(t) => t.to_string(),
            _ if simple(&self.text) => format!("~{}", self.text),
            _ => format!("~({})", self.text),
        };
        Expr {
            text,
            reads: self.reads.clone(),
        }
    }

    /// `parts` joined by `sep`, reading what each reads.
    pub(crate) fn join(parts: &[Expr], sep: &str) -> Expr {
        let mut e = Expr::constant(
            parts
                .iter()
                .map(|p| p.text.as_str())
                .collect::<Vec<_>>()
                .join(sep),
        );
        for p in parts {
            p.note_into(&mut e.reads);
        }
        e
    }
}

impl fmt::Display for Expr {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.text)
    }
}

/// A value written into an [`ex!`] expression: an [`Expr`] brings its reads; a number or a
/// constant's text reads nothing.
pub(crate) trait Part: fmt::Display {
    fn note_into(&self, _reads: &mut Vec<String>) {}
}

impl Part for Expr {
    fn note_into(&self, reads: &mut Vec<String>) {
        for r in &self.reads {
            if !reads.contains(r) {
                reads.push(r.clone());
            }
        }
    }
}
impl<T: Part + ?Sized> Part for &T {
    fn note_into(&self, reads: &mut Vec<String>) {
        (**self).note_into(reads)
    }
}
/// Constant text only (`lit`, a width): a signal's name comes as an [`Expr`].
impl Part for String {}
impl Part for str {}
impl Part for u32 {}
impl Part for usize {}
impl Part for u128 {}

/// Notes what `a` reads into `reads`, and gives `a` back to be written ([`ex!`]).
pub(crate) fn noted<'a, T: Part + ?Sized>(a: &'a T, reads: &mut Vec<String>) -> &'a T {
    a.note_into(reads);
    a
}

/// `ex!("{} + {}", a, b)`: an [`Expr`] whose text is formatted from positional arguments
/// (borrowed) and whose reads are theirs ([`Part`]).
macro_rules! ex {
    ($fmt:literal $(, $arg:expr)* $(,)?) => {{
        #[allow(unused_mut)]
        let mut reads: Vec<String> = Vec::new();
        let text = format!($fmt $(, $crate::datapath::expr::noted(&$arg, &mut reads))*);
        $crate::datapath::expr::Expr { text, reads }
    }};
}
pub(crate) use ex;
