//! The `fit` output of a saved corpus, reproduced bit for bit (every number
//! by its bits, whatever its text): the paper's examples, random y(x) with one or per-interval alphas, open and closed
//! curves in 2D and 3D with every parametrisation, values near the ends of
//! the double range (`tests/golden/cases.txt`). A change to the construction
//! that moves any digit fails here; one that is meant to says why in its
//! commit and saves the corpus again:
//!
//! ```sh
//! cd crates/bzspline-cli/tests/golden
//! grep -v '^#' cases.txt | while IFS='|' read -r name input args; do
//!     ../../../../target/debug/bzspline fit $input $args > $(echo $name).json
//! done
//! ```

use std::path::Path;
use std::process::Command;

use serde_json::Value;

const BIN: &str = env!("CARGO_BIN_EXE_bzspline");

#[test]
fn fit_reproduces_the_saved_corpus_bit_for_bit() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/golden");
    let cases = std::fs::read_to_string(dir.join("cases.txt")).unwrap();
    let mut checked = 0;
    for line in cases
        .lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
    {
        let parts: Vec<&str> = line.split('|').map(str::trim).collect();
        let [name, input, args] = parts[..] else {
            panic!("cases.txt: {line}")
        };
        let out = Command::new(BIN)
            .arg("fit")
            .args(input.split_whitespace())
            .args(args.split_whitespace())
            .current_dir(&dir)
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{name}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        let want = std::fs::read(dir.join(format!("{name}.json"))).unwrap();
        let (got, want): (Value, Value) = (
            serde_json::from_slice(&out.stdout).unwrap(),
            serde_json::from_slice(&want).unwrap(),
        );
        if let Some(at) = first_difference(&got, &want, String::new()) {
            panic!("{name}: the fit differs from the saved one at {at}:\n{got}");
        }
        checked += 1;
    }
    assert_eq!(checked, 42);
}

/// Where `got` and `want` differ: numbers by their bits (whatever their
/// text), strings word by word with the words that are numbers compared the
/// same way, everything else exactly.
fn first_difference(got: &Value, want: &Value, at: String) -> Option<String> {
    let same_number = |a: f64, b: f64| a.to_bits() == b.to_bits();
    match (got, want) {
        (Value::Number(a), Value::Number(b)) => {
            let (a, b) = (a.as_f64().unwrap(), b.as_f64().unwrap());
            (!same_number(a, b)).then(|| format!("{at}: {a:e} against {b:e}"))
        }
        (Value::String(a), Value::String(b)) => {
            let (wa, wb): (Vec<&str>, Vec<&str>) = (
                a.split_whitespace().collect(),
                b.split_whitespace().collect(),
            );
            let same = wa.len() == wb.len()
                && wa
                    .iter()
                    .zip(&wb)
                    .all(|(x, y)| match (x.parse::<f64>(), y.parse::<f64>()) {
                        (Ok(x), Ok(y)) => same_number(x, y),
                        _ => x == y,
                    });
            (!same).then(|| format!("{at}: the string differs"))
        }
        (Value::Array(a), Value::Array(b)) => {
            if a.len() != b.len() {
                return Some(format!("{at}: {} items against {}", a.len(), b.len()));
            }
            a.iter()
                .zip(b)
                .enumerate()
                .find_map(|(i, (x, y))| first_difference(x, y, format!("{at}[{i}]")))
        }
        (Value::Object(a), Value::Object(b)) => {
            if a.len() != b.len() || a.keys().zip(b.keys()).any(|(x, y)| x != y) {
                return Some(format!("{at}: the keys differ"));
            }
            a.iter()
                .zip(b.values())
                .find_map(|((k, x), y)| first_difference(x, y, format!("{at}.{k}")))
        }
        (a, b) => (a != b).then(|| format!("{at}: {a} against {b}")),
    }
}
