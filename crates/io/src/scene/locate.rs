//! Where a field of a scene is written in its RON text, so that a value
//! refused by validation is reported at its file, line and column like a
//! syntax error. A small scan of the text (strings and comments skipped):
//! struct keys (`name:`) and list elements (`[a, b]`) make the path;
//! struct and enum variant names (`Scene(`, `Sine(`) add nothing, so
//! `road: Sine(amplitude_m: 1e-3)` gives `road.amplitude_m`, as the
//! validation's field paths do.

/// Line and column (1-based) of every field and list element of `text`,
/// keyed by its path (`tyre.modes[0].damping_ratio`, `points[2]`).
fn paths(text: &str) -> Vec<(String, usize, usize)> {
    enum Frame {
        /// A struct, a variant or a map: the key being read.
        Fields(Option<String>),
        /// A list: the element being read, and whether it has started.
        List(usize, bool),
    }
    let prefix = |stack: &[Frame]| {
        let mut s = String::new();
        for f in stack {
            match f {
                Frame::Fields(Some(k)) => {
                    if !s.is_empty() {
                        s.push('.');
                    }
                    s.push_str(k);
                }
                Frame::Fields(None) => {}
                Frame::List(i, _) => s.push_str(&format!("[{i}]")),
            }
        }
        s
    };
    let chars: Vec<char> = text.chars().collect();
    let (mut line, mut col) = (1, 1);
    let mut out = Vec::new();
    let mut stack: Vec<Frame> = Vec::new();
    let mut k = 0;
    // advances over `n` chars, keeping line and column
    let step = |k: &mut usize, line: &mut usize, col: &mut usize, n: usize| {
        for _ in 0..n {
            if chars.get(*k) == Some(&'\n') {
                *line += 1;
                *col = 1;
            } else {
                *col += 1;
            }
            *k += 1;
        }
    };
    while k < chars.len() {
        let c = chars[k];
        // comments and strings say nothing about the structure
        if c == '/' && chars.get(k + 1) == Some(&'/') {
            while k < chars.len() && chars[k] != '\n' {
                step(&mut k, &mut line, &mut col, 1);
            }
            continue;
        }
        if c == '/' && chars.get(k + 1) == Some(&'*') {
            step(&mut k, &mut line, &mut col, 2);
            while k < chars.len() && !(chars[k] == '*' && chars.get(k + 1) == Some(&'/')) {
                step(&mut k, &mut line, &mut col, 1);
            }
            step(&mut k, &mut line, &mut col, 2);
            continue;
        }
        if c.is_whitespace() {
            step(&mut k, &mut line, &mut col, 1);
            continue;
        }
        // the first thing of a list element marks where it is written
        if let Some(Frame::List(i, started)) = stack.last_mut()
            && !*started
            && c != ']'
        {
            *started = true;
            let i = *i;
            let mut p = prefix(&stack[..stack.len() - 1]);
            p.push_str(&format!("[{i}]"));
            out.push((p, line, col));
        }
        match c {
            '"' => {
                step(&mut k, &mut line, &mut col, 1);
                while k < chars.len() && chars[k] != '"' {
                    let n = if chars[k] == '\\' { 2 } else { 1 };
                    step(&mut k, &mut line, &mut col, n);
                }
                step(&mut k, &mut line, &mut col, 1);
            }
            '(' | '{' => {
                stack.push(Frame::Fields(None));
                step(&mut k, &mut line, &mut col, 1);
            }
            '[' => {
                stack.push(Frame::List(0, false));
                step(&mut k, &mut line, &mut col, 1);
            }
            ')' | '}' | ']' => {
                stack.pop();
                step(&mut k, &mut line, &mut col, 1);
            }
            ',' => {
                match stack.last_mut() {
                    Some(Frame::List(i, started)) => {
                        *i += 1;
                        *started = false;
                    }
                    Some(Frame::Fields(key)) => *key = None,
                    None => {}
                }
                step(&mut k, &mut line, &mut col, 1);
            }
            c if c.is_alphabetic() || c == '_' => {
                let (l0, c0) = (line, col);
                let mut name = String::new();
                while k < chars.len() && (chars[k].is_alphanumeric() || chars[k] == '_') {
                    name.push(chars[k]);
                    step(&mut k, &mut line, &mut col, 1);
                }
                let mut j = k;
                while j < chars.len() && chars[j].is_whitespace() {
                    j += 1;
                }
                // `name:` in a struct is a key; anything else (a struct or
                // variant name, `true`, `inf`) is not
                if chars.get(j) == Some(&':')
                    && let Some(Frame::Fields(key)) = stack.last_mut()
                {
                    *key = Some(name);
                    out.push((prefix(&stack), l0, c0));
                }
            }
            _ => step(&mut k, &mut line, &mut col, 1),
        }
    }
    out
}

/// Line and column (1-based) where the field `path` of a validation error
/// is written in `text`: the field itself, else the nearest enclosing field
/// written (a value left to its default is reported at its parent). `None`
/// when nothing of the path is in the text.
pub fn locate(text: &str, path: &str) -> Option<(usize, usize)> {
    find(&paths(text), path)
}

/// [`locate`] of every path of `fields`, the text scanned once.
pub fn locate_all<'a>(
    text: &str,
    fields: impl IntoIterator<Item = &'a str>,
) -> Vec<Option<(usize, usize)>> {
    let all = paths(text);
    fields.into_iter().map(|f| find(&all, f)).collect()
}

fn find(all: &[(String, usize, usize)], path: &str) -> Option<(usize, usize)> {
    let mut p = path.trim().to_string();
    loop {
        if let Some(&(_, line, col)) = all.iter().find(|(q, _, _)| *q == p) {
            return Some((line, col));
        }
        // drop the last component: `a.b[2].c` -> `a.b[2]` -> `a.b` -> `a`
        let cut = p.rfind(['.', '['])?;
        p.truncate(cut);
        if p.is_empty() {
            return None;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::locate;

    const TEXT: &str = r#"// a scene
Scene(
    name: "a, [b]: (c)", /* not: a key */
    dt_s: 1e-5,
    road: Sine(amplitude_m: 1e-3, wavelength_m: 0.5),
    tyre: Modal(
        modes: [
            Mode(freq_hz: 100.0, damping_ratio: 0.05, residue: [[0.1, 0.2], [0.2, 0.3]]),
            Mode(freq_hz: 200.0, damping_ratio: -0.1),
        ],
    ),
    points: [(x_m: 0.0, h_m: -1e-3), (x_m: 0.1, h_m: -1e-3)],
)
"#;

    #[test]
    fn fields_are_found_at_their_line_and_column() {
        assert_eq!(locate(TEXT, "dt_s"), Some((4, 5)));
        // through a variant name: road.amplitude_m
        assert_eq!(locate(TEXT, "road.amplitude_m"), Some((5, 16)));
        assert_eq!(locate(TEXT, "road.wavelength_m"), Some((5, 35)));
        assert_eq!(locate(TEXT, "tyre.modes[1].damping_ratio"), Some((9, 34)));
        assert_eq!(locate(TEXT, "tyre.modes[0].residue[1][0]"), Some((8, 78)));
        assert_eq!(locate(TEXT, "points[1].h_m"), Some((12, 49)));
        assert_eq!(locate(TEXT, "points[1]"), Some((12, 38)));
        assert_eq!(locate(TEXT, "points"), Some((12, 5)));
    }

    #[test]
    fn a_field_not_written_is_reported_at_its_parent() {
        // mode 1 has no residue: its mode is where it is written
        assert_eq!(locate(TEXT, "tyre.modes[1].residue"), Some((9, 13)));
        assert_eq!(locate(TEXT, "duration_s"), None);
        // strings and comments hold no keys
        assert_eq!(locate(TEXT, "not"), None);
        assert_eq!(locate(TEXT, "b"), None);
    }
}
