//! Prints the coverage a `smooth_coverage` input decodes to, as GeoJSON
//! geometries one a line, then its options, the smoothed geometries and what
//! the judges say: `cargo run --example mosaic -- artifacts/smooth_coverage/crash-...`.

use bzspline_fuzz::judge::valid_stays_valid;
use bzspline_fuzz::mosaic;
use bzspline_geo::Coverage;
use geo_types::Geometry;
use libfuzzer_sys::arbitrary::Unstructured;

fn wkt(g: &Geometry<f64>) -> String {
    let ring = |l: &geo_types::LineString<f64>| {
        let p: Vec<String> =
            l.0.iter()
                .map(|c| format!("[{:?},{:?}]", c.x, c.y))
                .collect();
        format!("[{}]", p.join(","))
    };
    match g {
        Geometry::Polygon(p) => {
            let rs: Vec<String> = std::iter::once(p.exterior())
                .chain(p.interiors())
                .map(ring)
                .collect();
            format!(
                "{{\"type\":\"Polygon\",\"coordinates\":[{}]}}",
                rs.join(",")
            )
        }
        Geometry::LineString(l) => {
            format!("{{\"type\":\"LineString\",\"coordinates\":{}}}", ring(l))
        }
        other => format!("{other:?}"),
    }
}

fn main() {
    let path = std::env::args().nth(1).expect("a file");
    let bytes = std::fs::read(&path).expect("readable");
    let case = mosaic::case(&mut Unstructured::new(&bytes)).expect("a case");
    for g in &case.geometries {
        println!("{}", wkt(g));
    }
    println!(
        "opts {:?} snap {:?} exponent {} offset {}",
        case.opts, case.snap, case.exponent, case.offset
    );
    let c = Coverage::builder(case.geometries.clone())
        .snap(case.snap)
        .build()
        .expect("accepted");
    let (out, stats) = c.smooth(&case.opts).expect("smoothed");
    println!("{stats:?}");
    for g in &out {
        println!("{}", wkt(g));
    }
    println!("{:?}", valid_stays_valid(&case.geometries, &out));
}
