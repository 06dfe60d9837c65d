//! Folding the emitted Verilog's long lines at 120 characters, where a reader would.

use super::*;

/// The longest line the RTL holds.
pub(crate) const MAX_LINE: usize = 120;

/// A wire's statement: `wire [W-1:0] x_sK = expr;   // comment`, the comment on a line of its
/// own above it when the two do not fit one line.
pub(super) fn wire_statement(x: &Wire, step: usize) -> String {
    let range = if x.width == 1 {
        "      ".to_string()
    } else {
        format!("[{}:0]", x.width - 1)
    };
    // a kept wire is declared, then assigned: Icarus drops an attribute on a net declaration
    // assignment (and says so)
    let (decl, stmt) = match x.keep {
        true => (
            format!("(* keep *) wire {range} {}_s{step};\n", x.name),
            format!("assign {}_s{step} = {};", x.name, x.expr),
        ),
        false => (
            String::new(),
            format!("wire {range} {}_s{step} = {};", x.name, x.expr),
        ),
    };
    // an expression written one operand a line reads as few lines as fit
    let stmt = fill_lines(stmt.split("\n    "), " ", MAX_LINE).join("\n    ");
    let stmt = format!("{decl}{stmt}");
    if x.comment.is_empty() {
        return stmt;
    }
    let inline = format!("{stmt}   // {}", x.comment);
    if inline.lines().all(|l| l.chars().count() <= MAX_LINE) {
        inline
    } else {
        format!("// {}\n{stmt}", x.comment)
    }
}

/// Folds every line longer than [`MAX_LINE`] at a space: a comment continues as a comment, code
/// (never inside a string) on an indented line; a trailing comment moves to a line above.
pub(crate) fn fold_long_lines(text: &str) -> String {
    let mut out = String::with_capacity(text.len() + 64);
    for line in text.lines() {
        fold_line(line, &mut out);
    }
    if text.ends_with('\n') {
        out
    } else {
        out.trim_end_matches('\n').to_string()
    }
}

pub(super) fn fold_line(line: &str, out: &mut String) {
    let len = line.chars().count();
    if len <= MAX_LINE {
        out.push_str(line);
        out.push('\n');
        return;
    }
    let indent: String = line.chars().take_while(|c| *c == ' ').collect();
    let body = &line[indent.len()..];
    // where code ends and a trailing comment starts (outside strings)
    let mut in_string = false;
    let mut comment_at = None;
    let bytes = body.as_bytes();
    for i in 0..bytes.len() {
        match bytes[i] {
            b'"' => in_string = !in_string,
            b'/' if !in_string && bytes.get(i + 1) == Some(&b'/') => {
                comment_at = Some(i);
                break;
            }
            _ => {}
        }
    }
    match comment_at {
        Some(0) => wrap_words(&indent, body, "// ", "//     ", out),
        Some(i) => {
            fold_line(&format!("{indent}{}", body[i..].trim_end()), out);
            fold_line(&format!("{indent}{}", body[..i].trim_end()), out);
        }
        None => wrap_words(&indent, body, "", "    ", out),
    }
}

/// Breaks `body` at spaces outside strings; the first line keeps `first` after the indent, the
/// others get `rest` (a comment's text is taken from after its `// `).
pub(super) fn wrap_words(indent: &str, body: &str, first: &str, rest: &str, out: &mut String) {
    let text = body.strip_prefix(first).unwrap_or(body);
    let mut words: Vec<String> = Vec::new();
    let mut in_string = false;
    let mut cur = String::new();
    for c in text.chars() {
        if c == '"' {
            in_string = !in_string;
        }
        if c == ' ' && !in_string {
            words.push(std::mem::take(&mut cur));
        } else {
            cur.push(c);
        }
    }
    words.push(cur);
    let mut line = format!("{indent}{first}");
    let mut fresh = true;
    for w in words {
        if !fresh && line.chars().count() + 1 + w.chars().count() > MAX_LINE {
            out.push_str(line.trim_end());
            out.push('\n');
            line = format!("{indent}{rest}");
            fresh = true;
        }
        if !fresh {
            line.push(' ');
        }
        line.push_str(&w);
        fresh = false;
    }
    out.push_str(line.trim_end());
    out.push('\n');
}
