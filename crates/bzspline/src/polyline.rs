//! A polyline: points along a curve with the curve parameter of each, as
//! flattening, sampling and resampling return them.

/// Points along a curve, with the parameter of each.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Polyline {
    dim: usize,
    coords: Vec<f64>,
    params: Vec<f64>,
}

impl Polyline {
    pub(crate) fn new(dim: usize, coords: Vec<f64>, params: Vec<f64>) -> Self {
        Polyline {
            dim,
            coords,
            params,
        }
    }

    /// The dimension of the points.
    #[must_use]
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// Number of vertices.
    #[must_use]
    pub fn len(&self) -> usize {
        self.params.len()
    }

    /// True when there are no vertices.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.params.is_empty()
    }

    /// The vertices, flat, [`Polyline::dim`] numbers each.
    #[must_use]
    pub fn coords(&self) -> &[f64] {
        &self.coords
    }

    /// The curve parameter of each vertex.
    #[must_use]
    pub fn params(&self) -> &[f64] {
        &self.params
    }

    /// Vertex `i`.
    #[must_use]
    pub fn point(&self, i: usize) -> Option<&[f64]> {
        self.coords.get(i * self.dim..(i + 1) * self.dim)
    }

    /// The vertices as arrays; `None` when `D` is not the dimension.
    #[must_use]
    pub fn to_arrays<const D: usize>(&self) -> Option<Vec<[f64; D]>> {
        if D != self.dim {
            return None;
        }
        Some(
            self.coords
                .chunks_exact(D)
                .map(|c| {
                    let mut a = [0.0; D];
                    a.copy_from_slice(c);
                    a
                })
                .collect(),
        )
    }
}
