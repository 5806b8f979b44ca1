//! Finding figures in text: a pattern is literal text with holes for numbers, matched
//! against text whose runs of white space (line breaks included) are one space.

/// A piece of a pattern.
#[derive(Clone, Debug, PartialEq)]
enum Piece {
    Literal(String),
    /// A number; `true` where its value is wanted.
    Number(bool),
    /// Any text, as short as will do (`...` in printed output).
    Any,
}

/// A number as it was printed: its value and the half of its last printed digit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Printed {
    pub(super) value: f64,
    pub(super) half_digit: f64,
}

/// A pattern of literal text with holes for numbers and for any text.
pub(super) struct Pattern(Vec<Piece>);

impl Pattern {
    /// `text` with `{}`, `{_}` and `{..}` holes.
    pub(super) fn new(text: &str) -> Pattern {
        let mut pieces = Vec::new();
        let mut rest = squeeze(text);
        while let Some(at) = rest.find('{') {
            let (literal, hole) = rest.split_at(at);
            push_literal(&mut pieces, literal);
            let (piece, len) = if hole.starts_with("{}") {
                (Piece::Number(true), 2)
            } else if hole.starts_with("{_}") {
                (Piece::Number(false), 3)
            } else if hole.starts_with("{..}") {
                (Piece::Any, 4)
            } else {
                panic!("a pattern's holes are {{}}, {{_}} and {{..}}: {text}")
            };
            pieces.push(piece);
            rest = hole[len..].to_string();
        }
        push_literal(&mut pieces, &rest);
        Pattern(pieces)
    }

    /// A line of printed output as it must appear: `...` is any text, and a duration
    /// (a number before ` s`) any number, since times are the machine's.
    pub(super) fn printed_line(line: &str) -> Pattern {
        let mut pieces = Vec::new();
        for (k, part) in squeeze(line).split("...").enumerate() {
            if k > 0 {
                pieces.push(Piece::Any);
            }
            let mut literal = String::new();
            let mut rest = part;
            while !rest.is_empty() {
                match number_at(rest) {
                    Some((_, len)) if is_duration_unit(&rest[len..]) && starts_number(&literal) => {
                        push_literal(&mut pieces, &literal);
                        literal.clear();
                        pieces.push(Piece::Number(false));
                        rest = &rest[len..];
                    }
                    _ => {
                        let c = rest.chars().next().expect("not empty");
                        literal.push(c);
                        rest = &rest[c.len_utf8()..];
                    }
                }
            }
            push_literal(&mut pieces, &literal);
        }
        Pattern(pieces)
    }

    /// The wanted numbers of the first place in `text` that matches, if any.
    pub(super) fn find(&self, text: &str) -> Option<Vec<Printed>> {
        let text = squeeze(text);
        let starts: Vec<usize> = match self.0.first() {
            Some(Piece::Literal(l)) => text.match_indices(l.as_str()).map(|(i, _)| i).collect(),
            _ => text.char_indices().map(|(i, _)| i).collect(),
        };
        starts
            .into_iter()
            .find_map(|at| match_at(&self.0, &text, at, Vec::new()))
    }
}

fn push_literal(pieces: &mut Vec<Piece>, literal: &str) {
    if !literal.is_empty() {
        pieces.push(Piece::Literal(literal.to_string()));
    }
}

/// Whether `after` a number starts with the unit of seconds, ` s` alone.
fn is_duration_unit(after: &str) -> bool {
    after
        .strip_prefix(" s")
        .is_some_and(|rest| rest.chars().next().is_none_or(|c| !c.is_alphanumeric()))
}

/// Whether a number may start after `before`: not in the middle of a word or number.
fn starts_number(before: &str) -> bool {
    before
        .chars()
        .last()
        .is_none_or(|c| !c.is_ascii_alphanumeric() && c != '.' && c != '_')
}

/// `text` with each run of white space one space, trimmed.
fn squeeze(text: &str) -> String {
    text.split_whitespace().collect::<Vec<_>>().join(" ")
}

fn match_at(
    pieces: &[Piece],
    text: &str,
    at: usize,
    mut got: Vec<Printed>,
) -> Option<Vec<Printed>> {
    let Some((piece, rest)) = pieces.split_first() else {
        return Some(got);
    };
    let here = &text[at..];
    match piece {
        Piece::Literal(l) => here
            .starts_with(l.as_str())
            .then(|| match_at(rest, text, at + l.len(), got))
            .flatten(),
        Piece::Number(wanted) => {
            let (printed, len) = number_at(here)?;
            if *wanted {
                got.push(printed);
            }
            match_at(rest, text, at + len, got)
        }
        Piece::Any => here
            .char_indices()
            .map(|(i, _)| i)
            .chain(std::iter::once(here.len()))
            .find_map(|i| match_at(rest, text, at + i, got.clone())),
    }
}

/// The number `text` starts with and its length in bytes: an optional sign, digits with
/// optional thousands commas (`20,000`), an optional fraction and exponent.
fn number_at(text: &str) -> Option<(Printed, usize)> {
    let b = text.as_bytes();
    let mut i = usize::from(matches!(b.first(), Some(b'-' | b'+')));
    let digits = |i: &mut usize| {
        let start = *i;
        while b.get(*i).is_some_and(u8::is_ascii_digit) {
            *i += 1;
        }
        *i - start
    };
    if digits(&mut i) == 0 {
        return None;
    }
    while b.get(i) == Some(&b',')
        && b[i + 1..].iter().take_while(|c| c.is_ascii_digit()).count() == 3
    {
        i += 4;
    }
    let mut decimals = 0;
    if b.get(i) == Some(&b'.') && b.get(i + 1).is_some_and(u8::is_ascii_digit) {
        i += 1;
        decimals = digits(&mut i);
    }
    let mut exponent = 0i32;
    if matches!(b.get(i), Some(b'e' | b'E')) {
        let mut j = i + 1 + usize::from(matches!(b.get(i + 1), Some(b'-' | b'+')));
        if digits(&mut j) > 0 {
            exponent = text[i + 1..j].parse().expect("an exponent");
            i = j;
        }
    }
    let value: f64 = text[..i].replace(',', "").parse().ok()?;
    let half_digit = 0.5 * 10f64.powi(exponent - decimals as i32);
    Some((Printed { value, half_digit }, i))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn patterns_find_their_numbers() {
        let text = "| stable | 20,312 |\n  43.35 % | 42.66 – 44.04 % |";
        let got = Pattern::new("| stable | {} | {} % | {_} – {} % |")
            .find(text)
            .unwrap();
        let values: Vec<f64> = got.iter().map(|p| p.value).collect();
        assert_eq!(values, [20312.0, 43.35, 44.04]);
        assert_eq!(got[1].half_digit, 0.005);
        assert!(Pattern::new("| tipped | {} |").find(text).is_none());
        let any = Pattern::new("| stable |{..}– {} %").find(text).unwrap();
        assert_eq!(any[0].value, 44.04);
        let line = Pattern::printed_line("8000 samples simulated in 5.9 s, ...: done");
        assert_eq!(
            line.0
                .iter()
                .filter(|p| **p == Piece::Number(false))
                .count(),
            1
        );
        assert!(
            line.find("8000 samples simulated in 12.25 s, 3 rounds: done")
                .is_some()
        );
        assert!(
            line.find("8001 samples simulated in 5.9 s, 3 rounds: done")
                .is_none()
        );
        assert_eq!(number_at("1.5e-6 m").unwrap().0.value, 1.5e-6);
        assert_eq!(number_at("-0.010–0.040").unwrap().1, 6);
    }
}
