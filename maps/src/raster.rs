//! Georeferenced rasters: a grid of samples tied to map metres.
//!
//! Conventions, stated once for the whole project:
//! - map coordinates are metres, `x` = easting, `y` = northing;
//! - raster row 0 is the **north** edge, column 0 the **west** edge;
//! - `origin_m` is the map position of the north-west *corner* of pixel (0, 0);
//! - pixel `(col, row)` covers `x ∈ [ox + col·res, ox + (col+1)·res)` and
//!   `y ∈ (oy − (row+1)·res, oy − row·res]`; its centre is at half a pixel in.
//!
//! [`GeoTransform::pixel_of`] and [`GeoTransform::center_of`] are the only conversions between the
//! two frames; everything else calls them.

/// Where a raster sits on the map and how big its pixels are.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct GeoTransform {
    /// Map position (x east, y north, metres) of the north-west corner of pixel (0, 0).
    pub origin_m: [f64; 2],
    /// Pixel size in metres (square pixels).
    pub resolution_m_per_px: f64,
}

impl GeoTransform {
    /// A transform with the given north-west corner and pixel size.
    #[must_use]
    pub fn new(origin_x_m: f64, origin_y_m: f64, resolution_m_per_px: f64) -> Self {
        Self {
            origin_m: [origin_x_m, origin_y_m],
            resolution_m_per_px,
        }
    }

    /// The (column, row) of the pixel containing map point `(x_m, y_m)`, as real numbers
    /// (floor them to index). Column grows east, row grows south.
    #[must_use]
    pub fn pixel_of(&self, x_m: f64, y_m: f64) -> (f64, f64) {
        let res = self.resolution_m_per_px;
        (
            (x_m - self.origin_m[0]) / res,
            (self.origin_m[1] - y_m) / res,
        )
    }

    /// Map position of the centre of pixel `(col, row)`.
    #[must_use]
    pub fn center_of(&self, col: usize, row: usize) -> (f64, f64) {
        let res = self.resolution_m_per_px;
        (
            self.origin_m[0] + (col as f64 + 0.5) * res,
            self.origin_m[1] - (row as f64 + 0.5) * res,
        )
    }

    /// The transform of a raster covering the same ground with pixels `factor` times larger.
    #[must_use]
    pub fn scaled(&self, factor: f64) -> Self {
        Self {
            origin_m: self.origin_m,
            resolution_m_per_px: self.resolution_m_per_px * factor,
        }
    }
}

/// A georeferenced grid of samples, stored row-major from the north-west corner.
#[derive(Clone, Debug, PartialEq)]
pub struct Raster<T> {
    /// Width in pixels (columns).
    pub width: usize,
    /// Height in pixels (rows).
    pub height: usize,
    /// Placement on the map.
    pub geo: GeoTransform,
    /// `width * height` samples, row-major, row 0 = north edge.
    pub data: Vec<T>,
}

impl<T: Copy> Raster<T> {
    /// A raster filled with `value`.
    #[must_use]
    pub fn filled(width: usize, height: usize, geo: GeoTransform, value: T) -> Self {
        Self {
            width,
            height,
            geo,
            data: vec![value; width * height],
        }
    }

    /// Sample at `(col, row)`.
    ///
    /// # Panics
    /// If `col >= width` or `row >= height`.
    #[must_use]
    pub fn get(&self, col: usize, row: usize) -> T {
        assert!(
            col < self.width && row < self.height,
            "pixel ({col}, {row}) outside raster"
        );
        self.data[row * self.width + col]
    }

    /// Set the sample at `(col, row)`.
    ///
    /// # Panics
    /// If `col >= width` or `row >= height`.
    pub fn set(&mut self, col: usize, row: usize, value: T) {
        assert!(
            col < self.width && row < self.height,
            "pixel ({col}, {row}) outside raster"
        );
        self.data[row * self.width + col] = value;
    }

    /// The sample of the pixel containing map point `(x_m, y_m)`, or `None` off the raster.
    #[must_use]
    pub fn sample_nearest(&self, x_m: f64, y_m: f64) -> Option<T> {
        let (c, r) = self.geo.pixel_of(x_m, y_m);
        if !(c >= 0.0 && r >= 0.0) {
            return None;
        }
        let (c, r) = (c.floor() as usize, r.floor() as usize);
        (c < self.width && r < self.height).then(|| self.data[r * self.width + c])
    }

    /// Map extent as `(min_x, min_y, max_x, max_y)` in metres.
    #[must_use]
    pub fn extent_m(&self) -> (f64, f64, f64, f64) {
        let res = self.geo.resolution_m_per_px;
        let [ox, oy] = self.geo.origin_m;
        (
            ox,
            oy - self.height as f64 * res,
            ox + self.width as f64 * res,
            oy,
        )
    }

    /// Whether map point `(x_m, y_m)` lies on the raster.
    #[must_use]
    pub fn contains_point(&self, x_m: f64, y_m: f64) -> bool {
        let (x0, y0, x1, y1) = self.extent_m();
        x_m >= x0 && x_m < x1 && y_m > y0 && y_m <= y1
    }

    /// The `width × height` pixels starting at pixel `(col0, row0)`, placed where they lie on
    /// the map (the origin moves to the north-west corner of pixel `(col0, row0)`), or `None`
    /// if that window does not lie wholly on the raster (or `data` is not `width × height`
    /// long). An empty window (`width` or `height` 0) inside the raster is an empty raster.
    #[must_use]
    pub fn try_crop(
        &self,
        col0: usize,
        row0: usize,
        width: usize,
        height: usize,
    ) -> Option<Raster<T>> {
        let inside = |start: usize, len: usize, side: usize| {
            start.checked_add(len).is_some_and(|end| end <= side)
        };
        if !(inside(col0, width, self.width)
            && inside(row0, height, self.height)
            && self.width.checked_mul(self.height) == Some(self.data.len()))
        {
            return None;
        }
        let mut data = Vec::with_capacity(width * height);
        for row in row0..row0 + height {
            let start = row * self.width + col0;
            data.extend_from_slice(&self.data[start..start + width]);
        }
        let res = self.geo.resolution_m_per_px;
        Some(Raster {
            width,
            height,
            geo: GeoTransform::new(
                self.geo.origin_m[0] + col0 as f64 * res,
                self.geo.origin_m[1] - row0 as f64 * res,
                res,
            ),
            data,
        })
    }
}

impl Raster<f32> {
    /// Bilinear sample at map point `(x_m, y_m)` between pixel centres (clamped at the edges),
    /// or `None` off the raster.
    #[must_use]
    pub fn sample_bilinear(&self, x_m: f64, y_m: f64) -> Option<f32> {
        if !self.contains_point(x_m, y_m) {
            return None;
        }
        let (c, r) = self.geo.pixel_of(x_m, y_m);
        let (fc, fr) = ((c - 0.5).max(0.0), (r - 0.5).max(0.0));
        let (c0, r0) = (
            (fc.floor() as usize).min(self.width - 1),
            (fr.floor() as usize).min(self.height - 1),
        );
        let (c1, r1) = ((c0 + 1).min(self.width - 1), (r0 + 1).min(self.height - 1));
        let (tx, ty) = ((fc - c0 as f64) as f32, (fr - r0 as f64) as f32);
        let top = self.get(c0, r0) * (1.0 - tx) + self.get(c1, r0) * tx;
        let bottom = self.get(c0, r1) * (1.0 - tx) + self.get(c1, r1) * tx;
        Some(top * (1.0 - ty) + bottom * ty)
    }

    /// Terrain slope in degrees at every pixel, from central differences (one-sided at edges).
    ///
    /// # Units
    /// The raster holds heights in metres; the result holds degrees.
    #[must_use]
    pub fn slope_deg(&self) -> Raster<f32> {
        let g = self.gradient();
        Raster {
            width: g.width,
            height: g.height,
            geo: g.geo,
            data: g
                .data
                .iter()
                .map(|[dzdx, dzdy]| dzdx.hypot(*dzdy).atan().to_degrees())
                .collect(),
        }
    }

    /// The height gradient at every pixel, `[∂z/∂x (east), ∂z/∂y (north)]`, metres per metre,
    /// from central differences (one-sided at edges; zero on a raster under 2 × 2 pixels).
    #[must_use]
    pub fn gradient(&self) -> Raster<[f32; 2]> {
        let (w, h) = (self.width, self.height);
        let res = self.geo.resolution_m_per_px as f32;
        let mut out = Raster::filled(w, h, self.geo, [0.0f32; 2]);
        if w < 2 || h < 2 {
            return out;
        }
        for r in 0..h {
            let (ra, rb) = (r.saturating_sub(1), (r + 1).min(h - 1));
            for c in 0..w {
                let (ca, cb) = (c.saturating_sub(1), (c + 1).min(w - 1));
                let dzdx = (self.get(cb, r) - self.get(ca, r)) / ((cb - ca) as f32 * res);
                let dzdy = (self.get(c, ra) - self.get(c, rb)) / ((rb - ra) as f32 * res);
                out.data[r * w + c] = [dzdx, dzdy];
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pixel_and_centre_round_trip() {
        let g = GeoTransform::new(100.0, 500.0, 2.0);
        assert_eq!(g.center_of(0, 0), (101.0, 499.0));
        let (c, r) = g.pixel_of(101.0, 499.0);
        assert_eq!((c, r), (0.5, 0.5));
        let (c, r) = g.pixel_of(105.0, 490.0);
        assert_eq!((c.floor(), r.floor()), (2.0, 5.0));
    }

    #[test]
    fn nearest_sample_is_none_off_the_map() {
        let g = GeoTransform::new(0.0, 10.0, 1.0);
        let mut ras = Raster::filled(10, 10, g, 0u8);
        ras.set(3, 0, 7);
        assert_eq!(ras.sample_nearest(3.5, 9.5), Some(7));
        assert_eq!(ras.sample_nearest(-0.1, 5.0), None);
        assert_eq!(ras.sample_nearest(5.0, 10.5), None);
        assert_eq!(ras.sample_nearest(f64::NAN, 5.0), None);
    }

    #[test]
    fn crop_keeps_the_pixels_and_their_place_on_the_map() {
        let g = GeoTransform::new(100.0, 500.0, 2.0);
        let mut ras = Raster::filled(5, 4, g, 0u16);
        for (i, v) in ras.data.iter_mut().enumerate() {
            *v = i as u16;
        }
        let c = ras.try_crop(1, 2, 3, 2).unwrap_or_else(|| panic!("inside"));
        assert_eq!((c.width, c.height), (3, 2));
        assert_eq!(c.data, [11, 12, 13, 16, 17, 18]);
        assert_eq!(c.geo, GeoTransform::new(102.0, 496.0, 2.0));
        // Every pixel keeps its map position.
        assert_eq!(
            c.sample_nearest(103.0, 495.0),
            ras.sample_nearest(103.0, 495.0)
        );
        // The whole raster, an empty window, and windows past an edge or overflowing.
        assert_eq!(ras.try_crop(0, 0, 5, 4), Some(ras.clone()));
        assert_eq!(ras.try_crop(5, 4, 0, 0).map(|r| r.data.len()), Some(0));
        assert_eq!(ras.try_crop(3, 0, 3, 1), None);
        assert_eq!(ras.try_crop(0, 3, 1, 2), None);
        assert_eq!(ras.try_crop(6, 0, 0, 0), None);
        assert_eq!(ras.try_crop(usize::MAX, 0, 2, 1), None);
        let empty = Raster::filled(0, 0, g, 0u8);
        assert_eq!(empty.try_crop(0, 0, 1, 1), None);
    }

    #[test]
    fn slope_of_a_plane() {
        let g = GeoTransform::new(0.0, 10.0, 1.0);
        let mut dem = Raster::filled(10, 10, g, 0.0f32);
        for r in 0..10 {
            for c in 0..10 {
                dem.set(c, r, c as f32); // rises 1 m per metre east: 45 degrees
            }
        }
        let s = dem.slope_deg();
        assert!((s.get(5, 5) - 45.0).abs() < 1e-4);
    }
}
