//! Plate files refused: each bad row named by its line and what was expected there,
//! hostile counts refused before anything is reserved, and random and mutated files read
//! without a panic.

use super::Stream;
use super::plate::{Num, octahedron, plate_a, plate_b};
use touchdown::shape::{
    MAX_FACETS, MAX_LINE_BYTES, MAX_VERTICES, Polyhedron, parse_plate, parse_shape,
};

/// The octahedron in km as variant A (line 1 the counts, lines 2-7 the vertices, lines
/// 8-15 the facets), one line per element.
fn octahedron_lines() -> Vec<String> {
    plate_a(&octahedron(1.5), Num::Plain, "\n")
        .lines()
        .map(String::from)
        .collect()
}

fn refused(text: &str) -> String {
    match parse_shape(text, "t.tab", 1000.0) {
        Ok(m) => panic!("{text:?} read as {m:?}"),
        Err(e) => e.to_string(),
    }
}

/// Each bad row is refused naming the file, its line and what was expected there.
#[test]
fn bad_rows_are_refused_naming_the_line() {
    let good = octahedron_lines();
    assert_eq!(good.len(), 15);
    assert!(parse_shape(&(good.join("\n") + "\n"), "t.tab", 1000.0).is_ok());
    // (what, line to change (1-based), its new text (None: removed), the message)
    let cases: Vec<(&str, usize, Option<&str>, &str)> = vec![
        (
            "vertices out of order",
            3,
            Some("3 0 1.5 0"),
            "t.tab, line 3: expected vertex 2 (the rows number the 6 vertices 1 to 6 in order), \
             found '3'",
        ),
        (
            "a vertex row numbered 1.0",
            2,
            Some("1.0 1.5 0 0"),
            "line 2: expected vertex 1 (the rows number the 6 vertices 1 to 6 in order), \
             found '1.0'",
        ),
        (
            "facets out of order",
            9,
            Some("3 3 2 5"),
            "t.tab, line 9: expected facet 2 (the rows number the 8 facets 1 to 8 in order), \
             found '3'",
        ),
        (
            "vertex 0",
            8,
            Some("1 0 3 5"),
            "t.tab, line 8: vertex number 0: plate models number vertices from 1",
        ),
        (
            "vertex 7 of 6",
            15,
            Some("8 1 4 7"),
            "t.tab, line 15: vertex 7 does not exist (the model has 6 vertices)",
        ),
        (
            "a negative vertex",
            10,
            Some("3 -1 4 5"),
            "line 10: '-1' is not a vertex number",
        ),
        (
            "the last facet missing",
            15,
            None,
            "t.tab, line 15: the file ends before facet 8 of the 8 declared on line 1",
        ),
        (
            "a vertex row of 3 numbers",
            4,
            Some("3 0 1.5"),
            "t.tab, line 4: a vertex row has 4 numbers (i x y z), not 3: vertex 3 of 6 expected",
        ),
        (
            "a vertex row of 5 numbers",
            4,
            Some("3 0 1.5 0 1"),
            "line 4: a vertex row has 4 numbers (i x y z), not 5",
        ),
        (
            "a facet row of 3 numbers",
            12,
            Some("5 3 1"),
            "t.tab, line 12: a facet row has 4 numbers (j a b c), not 3: facet 5 of 8 expected",
        ),
        (
            "a facet row of 5 numbers",
            12,
            Some("5 3 1 6 2"),
            "line 12: a facet row has 4 numbers (j a b c), not 5",
        ),
        (
            "NaN",
            5,
            Some("4 0 NaN 0"),
            "t.tab, line 5: 'NaN' is not a finite number",
        ),
        (
            "infinity",
            5,
            Some("4 0 -inf 0"),
            "line 5: '-inf' is not a finite number",
        ),
        (
            "a number too large for f64",
            6,
            Some("5 0 0 1e999"),
            "line 6: '1e999' is not a finite number",
        ),
        (
            "a number too large in metres",
            6,
            Some("5 0 0 1e307"),
            "t.tab, line 6: '1e307' overflows in metres",
        ),
        (
            "not a number",
            7,
            Some("6 0 0 -1.5km"),
            "line 7: '-1.5km' is not a number",
        ),
        (
            "zero facets",
            1,
            Some("6 0"),
            "t.tab, line 1: 0 facets declared: a closed surface has at least 4",
        ),
        (
            "too few vertices",
            1,
            Some("  3   8"),
            "t.tab, line 1: 3 vertices declared: a closed surface has at least 4",
        ),
        (
            "one vertex too many declared",
            1,
            Some("7 8"),
            "t.tab, line 8: expected vertex 7 (the rows number the 7 vertices 1 to 7 in order), \
             found '1'",
        ),
        (
            "one facet too many declared",
            1,
            Some("6 9"),
            "t.tab, line 16: the file ends before facet 9 of the 9 declared on line 1",
        ),
        (
            "one facet too few declared",
            1,
            Some("6 7"),
            "t.tab, line 15: more than the 7 facets declared on line 1: the file goes on after \
             facet 7",
        ),
    ];
    for (what, line, new, message) in cases {
        let mut lines = good.clone();
        match new {
            Some(text) => lines[line - 1] = text.into(),
            None => {
                lines.remove(line - 1);
            }
        }
        let text = lines.join("\n") + "\n";
        let e = refused(&text);
        assert!(e.contains(message), "{what}: {e}");
        // The same with CRLF line ends.
        assert_eq!(refused(&(lines.join("\r\n") + "\r\n")), e, "{what}, CRLF");
    }
    let extra = good.join("\n") + "\n9 1 2 3\n\n";
    assert_eq!(
        refused(&extra),
        "t.tab, line 16: more than the 8 facets declared on line 1: the file goes on after \
         facet 8"
    );
    assert!(refused(&(good.join("\n") + "\n  x")).contains("line 16: more than the 8 facets"));
    let truncated = good[..4].join("\n");
    assert_eq!(
        refused(&truncated),
        "t.tab, line 5: the file ends before vertex 4 of the 6 declared on line 1"
    );

    // Variant B: its own facet count line.
    let b: Vec<String> = plate_b(&octahedron(1.5), Num::Plain, "\n")
        .lines()
        .map(String::from)
        .collect();
    assert_eq!(b.len(), 16);
    let with = |line: usize, text: &str| {
        let mut l = b.clone();
        l[line - 1] = text.into();
        l.join("\n") + "\n"
    };
    for (text, message) in [
        (
            with(8, "0"),
            "line 8: 0 facets declared: a closed surface has at least 4",
        ),
        (
            with(8, "8 9"),
            "line 8: expected the facet count (one number) after the 6 vertices declared on \
             line 1, found 2 numbers",
        ),
        (
            with(8, "7 0 0 0"),
            "line 8: expected the facet count (one number) after the 6 vertices declared on \
             line 1, found 4 numbers",
        ),
        (with(8, "x"), "line 8: 'x' is not a count of facets"),
        (
            with(8, "7"),
            "line 16: more than the 7 facets declared on line 8: the file goes on after facet 7",
        ),
        (
            b[..7].join("\n"),
            "line 8: the file ends before the facet count that follows the 6 vertices",
        ),
        (
            b[..9].join("\n"),
            "line 10: the file ends before facet 2 of the 8 declared on line 8",
        ),
    ] {
        let e = parse_plate(&text, "t.plt", 1.0).unwrap_err().to_string();
        assert!(
            e.starts_with("t.plt, ") && e.contains(message),
            "{text}: {e}"
        );
    }

    // The counts, as parse_plate reads them (the format's choice sends these to OBJ).
    for (text, message) in [
        (
            "",
            "t.tab, line 1: empty: a plate model starts with its counts",
        ),
        ("\n\n", "t.tab, line 3: empty"),
        (
            "6 8 1\n",
            "t.tab, line 1: a plate model starts with its counts, 'NV NF' or 'NV'",
        ),
        ("6 -8\n", "t.tab, line 1: '-8' is not a count of facets"),
        ("six\n", "t.tab, line 1: 'six' is not a count of vertices"),
    ] {
        let e = parse_plate(text, "t.tab", 1.0).unwrap_err().to_string();
        assert!(e.starts_with(message), "{text:?}: {e}");
    }
    // Numbers that are no counts open a plate model all the same (an OBJ line starts with
    // a keyword): refused as its header, not as an OBJ statement.
    for (text, message) in [
        (
            "-5 320\n1 0 0 0\n",
            "t.tab, line 1: '-5' is not a count of vertices",
        ),
        ("6 -8\n", "t.tab, line 1: '-8' is not a count of facets"),
        ("6.0 8\n", "t.tab, line 1: '6.0' is not a count of vertices"),
    ] {
        assert_eq!(refused(text), message, "{text:?}");
    }
    let long = format!("4 4\n1 0 0 0{}\n", " ".repeat(MAX_LINE_BYTES));
    assert_eq!(
        refused(&long),
        format!("t.tab, line 2: longer than {MAX_LINE_BYTES} bytes")
    );
    let e = parse_plate("4\n1 0 0 0\n\u{0}\u{1}é\n", "t.plt", 1.0)
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("t.plt, line 3: a vertex row has 4 numbers (i x y z), not 1"),
        "{e}"
    );
}

/// Counts above the limits are refused on the counts' line before a row is read or
/// anything reserved for them: a three-line file claiming a trillion vertices is refused
/// naming the count. Counts at the limits are accepted and the file read row by row.
#[test]
fn hostile_counts_are_refused_before_anything_is_reserved() {
    let rows = "1 0 0 0\n2 1 0 0\n";
    let trillion = format!("1000000000000 5\n{rows}");
    assert_eq!(
        refused(&trillion),
        format!(
            "t.tab, line 1: 1000000000000 vertices declared: touchdown reads shape models of \
             at most {MAX_VERTICES} vertices"
        )
    );
    let e = refused(&format!("6 1000000000000\n{rows}"));
    assert!(
        e.starts_with("t.tab, line 1: 1000000000000 facets declared")
            && e.contains(&format!("at most {MAX_FACETS} facets")),
        "{e}"
    );
    let digits = "9".repeat(40);
    let e = refused(&format!("{digits}\n{rows}"));
    assert!(
        e.starts_with("t.tab, line 1: '999999999999999999999999...' vertices declared"),
        "{e}"
    );
    let e = refused(&format!("{}\n", MAX_VERTICES + 1));
    assert!(
        e.starts_with(&format!("t.tab, line 1: {} vertices", MAX_VERTICES + 1)),
        "{e}"
    );
    let e = parse_plate(
        &format!(
            "4\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n{}\n",
            MAX_FACETS + 1
        ),
        "t.plt",
        1.0,
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.starts_with(&format!(
            "t.plt, line 6: {} facets declared",
            MAX_FACETS + 1
        )),
        "{e}"
    );
    let at_limit = format!("{MAX_VERTICES} {MAX_FACETS}\n{rows}");
    assert_eq!(
        refused(&at_limit),
        format!(
            "t.tab, line 4: the file ends before vertex 3 of the {MAX_VERTICES} declared on \
             line 1"
        )
    );
}

/// Read (by content, and as a plate), check and, if sound, evaluate: an answer and never a
/// panic.
fn survive(text: &str) -> bool {
    let _ = parse_plate(text, "fuzz.tab", 1000.0);
    let Ok(mesh) = parse_shape(text, "fuzz.tab", 1000.0) else {
        return false;
    };
    let Ok(checked) = mesh.check() else {
        return false;
    };
    let poly = Polyhedron::new(checked, 1000.0).unwrap();
    assert!(poly.field([1e4, 2e4, 3e4]).potential_m2_s2.is_finite());
    let _ = touchdown::shape::facets(&poly, [0.0, 0.0, 1.0], 1e-4);
    true
}

/// Sound plate files of both variants with bytes replaced, words replaced by hostile ones,
/// lines removed, repeated or swapped, and cut at every byte: read and checked without a
/// panic (seeded). Only the whole file (with or without its last newline) is sound when cut.
#[test]
fn random_and_mutated_plate_files_never_panic() {
    let mut s = Stream(0x2545_f491_4f6c_dd1d);
    let body = octahedron(1.5);
    let files = [
        plate_a(&body, Num::Plain, "\n"),
        plate_b(&body, Num::Exp, "\r\n"),
    ];
    let bytes = b"0123456789 \n\r\t-+.eE#xv\xff";
    let words = [
        "0",
        "1",
        "6",
        "7",
        "8",
        "-1",
        "4294967297",
        "99999999999999999999",
        "1000000000000",
        "5000000",
        "1e308",
        "-1e308",
        "nan",
        "inf",
        "1.",
        ".",
        "-",
        "v",
        "f",
        "",
    ];
    let sound = super::fuzz(
        &mut s,
        &files,
        (bytes, &words),
        [800, 800, 400, 1500],
        survive,
    );
    // Some changed bytes leave the body sound (a digit of a coordinate's fraction, say):
    // the mutations reach the end of the reader, not only its first refusals.
    assert!(sound > 0);
}
