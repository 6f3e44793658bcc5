//! Tells the tests what they can use: `cfg(atlas)` when `BZSPLINE_ATLAS`
//! names the folder of the public coverages (`bash bench/atlas.sh` fills it),
//! `cfg(gdal)` when GDAL's `ogrinfo` runs (Debian's `gdal-bin`), so that the
//! tests that need them run then and are reported as ignored otherwise.

fn main() {
    println!("cargo::rustc-check-cfg=cfg(atlas)");
    println!("cargo::rustc-check-cfg=cfg(gdal)");
    println!("cargo::rerun-if-env-changed=BZSPLINE_ATLAS");
    println!("cargo::rerun-if-env-changed=PATH");
    if std::env::var_os("BZSPLINE_ATLAS").is_some_and(|v| !v.is_empty()) {
        println!("cargo::rustc-cfg=atlas");
    }
    let gdal = std::process::Command::new("ogrinfo")
        .arg("--version")
        .output()
        .is_ok_and(|o| o.status.success());
    if gdal {
        println!("cargo::rustc-cfg=gdal");
    }
}
