//! Arguments from JavaScript: numbers and arrays of numbers, option objects,
//! and the errors thrown back. Each module build (curves, smoothing, maps)
//! uses part of them.
#![cfg_attr(
    not(all(feature = "curves", feature = "smoothing", feature = "geo")),
    allow(dead_code)
)]

use bzspline::AlphaChoice;
#[cfg(feature = "geo")]
use bzspline_io::distance::{parse_distance, Distance};
use js_sys::{Array, Float64Array, Reflect};
use wasm_bindgen::{JsCast, JsValue};

/// A `RangeError` with the message.
pub fn range_error(msg: impl std::fmt::Display) -> JsValue {
    js_sys::RangeError::new(&msg.to_string()).into()
}

/// A `TypeError` with the message.
pub fn type_error(msg: impl std::fmt::Display) -> JsValue {
    js_sys::TypeError::new(&msg.to_string()).into()
}

/// `o[name] = v`.
pub fn set(o: &js_sys::Object, name: &str, v: JsValue) {
    // Setting a property of a fresh plain object cannot fail.
    let _ = Reflect::set(o, &JsValue::from_str(name), &v);
}

/// A library error as a `RangeError`.
pub fn lib_error(e: bzspline::Error) -> JsValue {
    range_error(e)
}

/// The numbers of an array-like of numbers (a typed array, an Array of
/// numbers, anything `Float64Array.from` reads); `what` names it in errors.
/// Entries that are not numbers are a `TypeError` naming the index.
pub fn numbers(v: &JsValue, what: &str) -> Result<Vec<f64>, JsValue> {
    if let Some(a) = v.dyn_ref::<Float64Array>() {
        return Ok(a.to_vec());
    }
    if let Some(a) = v.dyn_ref::<Array>() {
        let mut out = Vec::with_capacity(a.length() as usize);
        for (i, item) in a.iter().enumerate() {
            match item.as_f64() {
                Some(x) => out.push(x),
                None => {
                    return Err(type_error(format!(
                        "{what}[{i}] is not a number (found {})",
                        kind(&item)
                    )))
                }
            }
        }
        return Ok(out);
    }
    if js_sys::ArrayBuffer::is_view(v) && !v.is_instance_of::<js_sys::DataView>() {
        return Ok(Float64Array::new(v).to_vec());
    }
    Err(type_error(format!(
        "{what} must be an array or a typed array of numbers (found {})",
        kind(v)
    )))
}

/// The points of an array of points (`[[x, y], ...]`, all of one
/// dimension) as one flat array and the dimension.
pub fn points(v: &JsValue, what: &str) -> Result<(Vec<f64>, usize), JsValue> {
    let Some(a) = v.dyn_ref::<Array>() else {
        return Err(type_error(format!(
            "{what} must be an array of points ([[x, y], ...]; found {})",
            kind(v)
        )));
    };
    let mut flat = Vec::new();
    let mut dim = 0;
    for (i, p) in a.iter().enumerate() {
        let row = numbers(&p, &format!("{what}[{i}]"))?;
        if i == 0 {
            dim = row.len();
            if dim == 0 {
                return Err(range_error(format!("{what}[0] has no coordinates")));
            }
        } else if row.len() != dim {
            return Err(range_error(format!(
                "{what}[{i}] has {} coordinates, {what}[0] has {dim}",
                row.len()
            )));
        }
        flat.extend_from_slice(&row);
    }
    Ok((flat, dim))
}

/// What a value is, for messages.
pub fn kind(v: &JsValue) -> String {
    if v.is_null() {
        "null".into()
    } else if v.is_undefined() {
        "undefined".into()
    } else if let Some(s) = v.as_string() {
        format!("the string \"{s}\"")
    } else {
        v.js_typeof().as_string().unwrap_or_default()
    }
}

/// An options object (`undefined` and `null` are no options).
pub struct Options(Option<JsValue>);

impl Options {
    /// Reads `v` as an options object.
    pub fn new(v: &JsValue) -> Result<Self, JsValue> {
        if v.is_undefined() || v.is_null() {
            Ok(Options(None))
        } else if v.is_object() && !Array::is_array(v) {
            Ok(Options(Some(v.clone())))
        } else {
            Err(type_error(format!(
                "options must be an object (found {})",
                kind(v)
            )))
        }
    }

    /// The value of `name`, `None` when absent or undefined.
    pub fn get(&self, name: &str) -> Option<JsValue> {
        let o = self.0.as_ref()?;
        let v = Reflect::get(o, &JsValue::from_str(name)).ok()?;
        (!v.is_undefined()).then_some(v)
    }

    /// A boolean option.
    pub fn flag(&self, name: &str, default: bool) -> Result<bool, JsValue> {
        match self.get(name) {
            None => Ok(default),
            Some(v) => v.as_bool().ok_or_else(|| {
                type_error(format!("{name} must be true or false (found {})", kind(&v)))
            }),
        }
    }

    /// The smoothing options `w` (one weight per point, `null` or absent for
    /// all 1) and `lam` (absent or `null`: chosen by cross-validation).
    pub fn smoothing(&self) -> Result<(Option<Vec<f64>>, bzspline::Smoothing), JsValue> {
        let w = self
            .get("w")
            .filter(|v| !v.is_null())
            .map(|v| numbers(&v, "w"))
            .transpose()?;
        let how = match self.number("lam")? {
            None => bzspline::Smoothing::Gcv,
            Some(l) => bzspline::Smoothing::Lambda(l),
        };
        Ok((w, how))
    }

    /// A number option (`null` is none).
    pub fn number(&self, name: &str) -> Result<Option<f64>, JsValue> {
        self.typed(name, "a number", JsValue::as_f64)
    }

    /// A distance option: a number in the data's units, or a string with a
    /// unit (`"50m"`, `"2km"`, `"0.001deg"`) read by
    /// [`bzspline_io::distance::parse_distance`] (`null` is none).
    #[cfg(feature = "geo")]
    pub fn distance(&self, name: &str) -> Result<Option<Distance>, JsValue> {
        match self.get(name) {
            None => Ok(None),
            Some(v) if v.is_null() => Ok(None),
            Some(v) => match (v.as_f64(), v.as_string()) {
                (Some(x), _) => Ok(Some(Distance::data(x))),
                (None, Some(s)) => parse_distance(&s)
                    .map(Some)
                    .map_err(|e| range_error(format!("{name} {e}"))),
                _ => Err(type_error(format!(
                    "{name} must be a number or a string such as \"50m\" (found {})",
                    kind(&v)
                ))),
            },
        }
    }

    /// A string option (`null` is none).
    pub fn string(&self, name: &str) -> Result<Option<String>, JsValue> {
        self.typed(name, "a string", JsValue::as_string)
    }

    /// The option `name` read by `read`, `None` when absent or `null`, a
    /// `TypeError` saying it must be `what` otherwise.
    fn typed<T>(
        &self,
        name: &str,
        what: &str,
        read: impl Fn(&JsValue) -> Option<T>,
    ) -> Result<Option<T>, JsValue> {
        match self.get(name) {
            None => Ok(None),
            Some(v) if v.is_null() => Ok(None),
            Some(v) => read(&v)
                .map(Some)
                .ok_or_else(|| type_error(format!("{name} must be {what} (found {})", kind(&v)))),
        }
    }

    /// The shape parameters: `alpha` (one number) or `alphas` (one per
    /// interval), not both.
    pub fn alphas(&self) -> Result<AlphaChoice, JsValue> {
        let one = match self.get("alpha") {
            None => None,
            Some(v) => Some(alpha_value(&v)?),
        };
        match (one, self.get("alphas")) {
            (Some(_), Some(_)) => Err(type_error("give alpha or alphas, not both")),
            (Some(a), None) => Ok(AlphaChoice::One(a)),
            (None, Some(v)) => Ok(AlphaChoice::Each(numbers(&v, "alphas")?)),
            (None, None) => Ok(AlphaChoice::default()),
        }
    }
}

/// One alpha: a number (write a third as `1/3`, which JavaScript evaluates
/// to the nearest double, as the command reads its text `"1/3"`). A string
/// is a `TypeError`: reading decimal text would take Rust's float parser into
/// the module (about 14 kB of it gzipped). The range is checked where the
/// number is used (by the library, or `checkAlpha`).
pub fn alpha_value(v: &JsValue) -> Result<f64, JsValue> {
    v.as_f64().ok_or_else(|| {
        type_error(format!(
            "alpha must be a number, such as 1/3 (found {})",
            kind(v)
        ))
    })
}

/// The `param` option: a name or the parameters themselves.
pub fn param_of(o: &Options) -> Result<bzspline::Param, JsValue> {
    match o.get("param") {
        None => Ok(bzspline::Param::default()),
        Some(v) => match v.as_string() {
            Some(s) => s.parse::<bzspline::Param>().map_err(range_error),
            None if v.is_object() => Ok(bzspline::Param::Given(numbers(&v, "param")?)),
            None => Err(type_error(format!(
                "param must be a name or an array of parameters (found {})",
                kind(&v)
            ))),
        },
    }
}
