//! The zones of an imported scenario (a modelling choice: the record has no zones): a keep-in
//! corridor along the route and narrow passages across it, by the rule of
//! [`super::ImportOptions`] ([`Imported::place_passages`]).

use super::polyline::{along, point_at, round1};
use super::{Imported, PAPER_000_385_FAULT_R_M};

/// Half-width of the keep-in corridor along the route, metres: the passages' blocks reach
/// [`PASSAGE_REACH_M`] to either side, past its edge, so no detour goes around them.
pub const CORRIDOR_HALF_WIDTH_M: f64 = 150.0;
/// How far a passage's blocks reach from the gap, metres.
pub const PASSAGE_REACH_M: f64 = 180.0;

/// Half a planning-grid cell, metres: the grid measures a gap to cell centres, so it is added
/// to each passage's half gap for the clearance `solsim validate` reports to be the intended
/// one within a cell (the imported scenarios' grid is 2 m).
const GRID_HALF_CELL_M: f64 = 1.0;

impl Imported {
    /// The keep-in corridor: the route buffered by [`CORRIDOR_HALF_WIDTH_M`] (round joins), a
    /// GeoJSON feature (a modelling choice, as the rover planners' keep-in zones of paper 000
    /// Fig. 3).
    fn corridor(&self) -> String {
        use geo::Buffer as _;
        let line = geo::LineString::from(
            self.route_m
                .iter()
                .map(|p| (p[0], p[1]))
                .collect::<Vec<_>>(),
        );
        let area = line.buffer(CORRIDOR_HALF_WIDTH_M);
        let ring = |r: &geo::LineString<f64>| -> String {
            let pts: Vec<String> =
                r.0.iter()
                    .map(|c| format!("[{}, {}]", round1(c.x), round1(c.y)))
                    .collect();
            format!("[{}]", pts.join(", "))
        };
        let polygons: Vec<String> = area
            .0
            .iter()
            .map(|p| {
                let mut rings = vec![ring(p.exterior())];
                rings.extend(p.interiors().iter().map(ring));
                format!("[{}]", rings.join(", "))
            })
            .collect();
        format!(
            r#"{{"type": "Feature", "properties": {{"kind": "keep_in", "name": "corridor {CORRIDOR_HALF_WIDTH_M} m either side of the recorded route"}}, "geometry": {{"type": "MultiPolygon", "coordinates": [{}]}}}}"#,
            polygons.join(", ")
        )
    }

    /// The zones: the passages of the import rule, placed with each sol's start at
    /// `sol_start_along_m[i]` metres along the route (the first placement takes the recorded
    /// path's; `solsim record import` places them again where the replay, run without them,
    /// starts each sol, so the replay meets each passage where the rule says). Returns the
    /// GeoJSON and the number of passages.
    #[must_use]
    pub fn place_passages(&self, sol_start_along_m: &[f64]) -> (String, usize) {
        let opts = &self.options;
        let cum = along(&self.route_m);
        let mut zones: Vec<String> = Vec::new();
        let mut last_passage = f64::NEG_INFINITY;
        for (i, x) in self.sols.iter().enumerate() {
            let Some(&start) = sol_start_along_m.get(i) else {
                break;
            };
            if x.distance_m <= 0.0 {
                continue;
            }
            if x.no_path {
                // The fault: 20 m past the paper's distance into the sol, closing at paper
                // 000's radius at the fault.
                let at = start + x.distance_m + 20.0;
                let (p, d) = point_at(&self.route_m, &cum, at);
                let half = PAPER_000_385_FAULT_R_M + opts.footprint_radius_m + GRID_HALF_CELL_M;
                zones.extend(passage_features(
                    &format!(
                        "sol {} passage (NO_PATH, paper 000 Fig. 4; {at:.0} m along the route)",
                        x.sol
                    ),
                    p,
                    d,
                    half,
                ));
                last_passage = at;
            } else if x.from_fix
                && x.distance_m > 2.0 * opts.passage_into_sol_m
                && start + opts.passage_into_sol_m - last_passage >= opts.passage_spacing_m
            {
                let at = start + opts.passage_into_sol_m;
                let (p, d) = point_at(&self.route_m, &cum, at);
                let half = opts.passage_clearance_m + opts.footprint_radius_m + GRID_HALF_CELL_M;
                zones.extend(passage_features(
                    &format!("sol {} passage ({at:.0} m along the route)", x.sol),
                    p,
                    d,
                    half,
                ));
                last_passage = at;
            }
        }
        let n = zones.len() / 2;
        zones.push(self.corridor());
        (
            format!(
                "{{\"type\": \"FeatureCollection\", \"features\": [\n{}\n]}}\n",
                zones.join(",\n")
            ),
            n,
        )
    }
}

/// Two keep-out blocks across the path at `p` (unit direction `d`), leaving a gap of
/// `2 × half_gap_m` centred on the path: GeoJSON features.
fn passage_features(name: &str, p: [f64; 2], d: [f64; 2], half_gap_m: f64) -> [String; 2] {
    let n = [-d[1], d[0]];
    let (thick, reach) = (20.0, PASSAGE_REACH_M);
    let block = |side: f64, label: &str| {
        let corner = |u: f64, v: f64| {
            [
                round1(p[0] + d[0] * u + n[0] * v * side),
                round1(p[1] + d[1] * u + n[1] * v * side),
            ]
        };
        let ring = [
            corner(-thick / 2.0, half_gap_m),
            corner(thick / 2.0, half_gap_m),
            corner(thick / 2.0, half_gap_m + reach),
            corner(-thick / 2.0, half_gap_m + reach),
            corner(-thick / 2.0, half_gap_m),
        ];
        let coords: Vec<String> = ring
            .iter()
            .map(|c| format!("[{}, {}]", c[0], c[1]))
            .collect();
        format!(
            r#"{{"type": "Feature", "properties": {{"kind": "keep_out", "name": "{name} {label}"}}, "geometry": {{"type": "Polygon", "coordinates": [[{}]]}}}}"#,
            coords.join(", ")
        )
    };
    [block(1.0, "left"), block(-1.0, "right")]
}
