//! The result of one localization on user rasters, for people and for programs: the verdict,
//! the table, the JSON document, and the warnings about DEMs that take no part.

use std::path::PathBuf;

use serde_json::json;

use super::inputs::{LocalizeInputs, LocalizeRequest};
use crate::matcher::MatchResult;

/// `ACCEPTED` or `REJECTED: reason`.
#[must_use]
pub fn verdict(m: &MatchResult) -> String {
    match &m.rejection {
        None => "ACCEPTED".to_owned(),
        Some(r) => format!("REJECTED: {r}"),
    }
}

/// The result as a table.
#[must_use]
pub fn table(inp: &LocalizeInputs, m: &MatchResult) -> String {
    let dem_used = inp.dem_used();
    let [px, py] = inp.prior_m;
    let [x, y] = m.position_m;
    let [dx, dy] = m.correction_m;
    let terms = match (dem_used, inp.map_dem.is_some() && inp.rover_dem.is_some()) {
        (true, _) => "appearance + DEM",
        (false, true) => "appearance only (the map DEM does not cover the search window)",
        (false, false) => "appearance only",
    };
    format!(
        "solsim localize: {} around the prior (E {px:.3}, N {py:.3}) m, search radius {} m\n\
         \x20 score terms     {terms}\n\
         \x20 position        E {x:.3} m, N {y:.3} m\n\
         \x20 correction      E {dx:+.3} m, N {dy:+.3} m ({:.3} m)\n\
         \x20 sigma           {:.3} m\n\
         \x20 best score      {:.4} (lower is better)\n\
         \x20 peak ratio      {:.3} (runner-up minimum / best)\n\
         \x20 valid fraction  {:.3}\n\
         \x20 verdict         {}\n",
        inp.params.method,
        inp.params.search_radius_m,
        dx.hypot(dy),
        m.sigma_m,
        m.best_score,
        m.peak_ratio,
        m.valid_fraction,
        verdict(m)
    )
}

/// The result as a JSON document: the inputs, `result` (the matcher's [`MatchResult`] as
/// serialized), `accepted`, `verdict` and `dem_used`.
#[must_use]
pub fn json_doc(a: &LocalizeRequest, inp: &LocalizeInputs, m: &MatchResult) -> serde_json::Value {
    let path = |p: &Option<PathBuf>| p.as_ref().map(|p| p.display().to_string());
    json!({
        // Every crate of the workspace carries solsim's version.
        "solsim_version": env!("CARGO_PKG_VERSION"),
        "inputs": {
            "map_appearance": a.map_appearance.display().to_string(),
            "map_dem": path(&a.map_dem),
            "ortho": a.ortho.display().to_string(),
            "ortho_valid": path(&a.ortho_valid),
            "rover_dem": path(&a.rover_dem),
            "rover_dem_valid": path(&a.rover_dem_valid),
            "resolution_m_per_px": inp.appearance.geo.resolution_m_per_px,
            "prior_m": inp.prior_m,
            "params": inp.params,
        },
        "result": m,
        "accepted": m.rejection.is_none(),
        "verdict": verdict(m),
        "dem_used": inp.dem_used(),
    })
}

/// Why a DEM given takes no part in the match, one sentence each: one DEM without the other,
/// or a map DEM that does not cover the search window with the rover DEM around it.
#[must_use]
pub fn warnings(a: &LocalizeRequest, inp: &LocalizeInputs) -> Vec<String> {
    let mut w = Vec::new();
    match (&a.map_dem, &a.rover_dem) {
        (Some(_), None) => {
            w.push("--map-dem given without --rover-dem: the DEM term is not used".to_owned());
        }
        (None, Some(_)) => {
            w.push("--rover-dem given without --map-dem: the DEM term is not used".to_owned());
        }
        _ => {}
    }
    if let (Some(path), Some(_), false) = (&a.map_dem, &a.rover_dem, inp.dem_used()) {
        w.push(format!(
            "--map-dem {} does not cover the search window with the rover DEM around it: the \
             DEM term is not used",
            path.display()
        ));
    }
    w
}
