//! Tells the tests whether the public coverages are there: `cfg(atlas)` when
//! `BZSPLINE_ATLAS` names their folder (`bash bench/atlas.sh` fills it), so
//! that `tests/atlas.rs` runs them then and reports them as ignored otherwise.

fn main() {
    println!("cargo::rustc-check-cfg=cfg(atlas)");
    println!("cargo::rerun-if-env-changed=BZSPLINE_ATLAS");
    if std::env::var_os("BZSPLINE_ATLAS").is_some_and(|v| !v.is_empty()) {
        println!("cargo::rustc-cfg=atlas");
    }
}
