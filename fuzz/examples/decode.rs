//! Prints the data set a fuzzer input decodes to: `cargo run --example decode -- FILE`.
fn main() {
    for path in std::env::args().skip(1) {
        let bytes = std::fs::read(&path).unwrap_or_default();
        let d = bzspline_fuzz::Data::decode(&mut bzspline_fuzz::Reader::new(&bytes));
        println!("{path}: {d:?}");
    }
}
