//! Evaluating a spline at arbitrary points under every extrapolation policy:
//! values, derivatives of any order, the batch evaluators, integrals, extrema.
//! Every answer is a finite number or a typed error, never a panic, and the
//! batch answers equal the one-by-one answers.
#![no_main]

use bzspline::ParamCurve;
use bzspline::{Error, Extrapolate, Spline};
use bzspline_fuzz::{Data, Reader};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|bytes: &[u8]| {
    let mut r = Reader::new(bytes);
    let d = Data::decode(&mut r);
    let Ok(s) = Spline::with_alphas(&d.knots, &d.values, &d.alphas) else {
        return;
    };
    let policy = match r.u8() % 3 {
        0 => Extrapolate::Error,
        1 => Extrapolate::Clamp,
        _ => Extrapolate::Extend,
    };
    let s = s.with_extrapolation(policy);
    let (a, b) = s.domain();
    let mut xs = Vec::new();
    while !r.is_empty() && xs.len() < 64 {
        let x = match r.u8() % 8 {
            0 => r.raw_f64(),
            1 => a,
            2 => b,
            3 => d.knots[usize::from(r.u8()) % d.knots.len()],
            4 => a.next_down(),
            5 => b.next_up(),
            // Inside the domain, or just beyond it.
            _ => a + (b - a) * (f64::from(r.u16()) / 65535.0 * 1.2 - 0.1),
        };
        xs.push(x);
    }
    let order = u32::from(r.u8()) % 6;
    for &x in &xs {
        match s.deriv(x, order) {
            Ok(v) => assert!(v.is_finite(), "{policy:?}: S^({order})({x}) = {v}"),
            Err(e) => check_error(&s, x, &e),
        }
        if let Ok(all) = s.eval_all(x) {
            assert!(all.iter().all(|v| v.is_finite()), "eval_all({x}) = {all:?}");
            if order < 4 {
                assert_eq!(Some(all[order as usize]), s.deriv(x, order).ok());
            }
        }
        if x >= a && x <= b {
            // Inside the domain the value always exists.
            let y = s.eval(x).expect("inside the domain");
            assert!(y.is_finite());
        }
        match s.integral(a, x) {
            Ok(v) => assert!(v.is_finite(), "integral to {x} = {v}"),
            Err(e) => check_error(&s, x, &e),
        }
        if let (Ok(u), Ok(v)) = (s.integral(a, x), s.integral(x, a)) {
            assert_eq!(u, -v, "integral is antisymmetric");
        }
    }
    let mut out = vec![0.0; xs.len()];
    if s.deriv_many(&xs, order, &mut out).is_ok() {
        for (x, y) in xs.iter().zip(&out) {
            assert_eq!(s.deriv(*x, order).ok(), Some(*y), "batch vs single at {x}");
        }
    }
    let mut short = vec![0.0; xs.len() + 1];
    assert!(matches!(
        s.eval_many(&xs, &mut short),
        Err(Error::LengthMismatch { .. })
    ));
    let ((x0, y0), (x1, y1)) = s.range();
    assert!([x0, y0, x1, y1].iter().all(|v| v.is_finite()));
    let ext = s.extrema();
    assert!(ext.windows(2).all(|w| w[0].x < w[1].x), "extrema sorted");
    for _ in 0..s.len().min(4) {
        let k = s.piece_index(r.raw_f64());
        assert!(k < s.len());
    }
});

/// An error at query `x` must be justified.
fn check_error(s: &Spline, x: f64, e: &Error) {
    let (a, b) = s.domain();
    match *e {
        Error::NonFinite { value, .. } => assert!(!value.is_finite()),
        Error::OutOfDomain { x: q, .. } => {
            assert!(
                s.extrapolation() == Extrapolate::Error && !(a..=b).contains(&q),
                "{e} at {x}"
            );
        }
        Error::Overflow { .. } => {}
        _ => panic!("unexpected error {e} at {x}"),
    }
}
