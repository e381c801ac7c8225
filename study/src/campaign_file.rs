//! Campaign files (TOML) → a validated [`planner::Problem`] for one sol.
//!
//! Two-stage loading like [`crate::scenario`]: `RawCampaignFile` mirrors the file exactly
//! (`deny_unknown_fields`); [`CampaignFile::load`] checks every field, converts LMST clock
//! readings to seconds after local midnight (a sol is 88 775 s) and minutes to seconds, and
//! expands periodic and state-based campaigns into instance activities with
//! [`planner::periodic_instances`] and [`planner::state_based_instances`]. Every error is one
//! line naming the file and the TOML field.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use planner::{PlanError, Problem};

use crate::check::FieldCheck;
use crate::error::ScenarioError;
use activity_entry::activity;
pub(crate) use campaign_entry::{campaign, task};
use raw::RawCampaignFile;

mod activity_entry;
mod campaign_entry;
pub(crate) mod raw;

pub use activity_entry::{DEFAULT_MAX_SEGMENTS, DEFAULT_MIN_SEGMENT_MIN};

/// Why a campaign file cannot be planned. Displayed as one line naming the file and field.
#[derive(Debug, thiserror::Error)]
pub enum PlanFileError {
    /// The file could not be read or parsed, or a field is out of range.
    #[error(transparent)]
    File(#[from] ScenarioError),
    /// The planner rejected the problem the file describes.
    #[error("{path}: {field}: {error}")]
    Planner {
        /// The campaign file.
        path: PathBuf,
        /// TOML path of the activity or campaign at fault, e.g. `activities[2]`.
        field: String,
        /// The planner's reason.
        error: PlanError,
    },
}

/// A validated campaign file.
#[derive(Debug, Clone)]
pub struct CampaignFile {
    /// The file it came from.
    pub path: PathBuf,
    /// Short name (default: the file stem).
    pub name: String,
    /// One-paragraph description.
    pub description: String,
    /// SHA-256 of the file's bytes, hex.
    pub sha256: String,
    /// The planning problem, times in s after local midnight.
    pub problem: Problem,
    /// For each activity of `problem`, the TOML path it came from (`activities[3]`, or
    /// `campaigns[1].template` for generated instances).
    pub origins: Vec<String>,
}

impl CampaignFile {
    /// Read, validate and expand a campaign file.
    ///
    /// # Errors
    /// A [`PlanFileError`] naming the file and the first field at fault.
    pub fn load(path: &Path) -> Result<Self, PlanFileError> {
        let (raw, sha256) = crate::input::read_toml::<RawCampaignFile>(path)?;
        Self::checked(path, raw, sha256)
    }

    /// [`CampaignFile::load`] of campaign-file text (`path` names it in errors; nothing is
    /// read): what the fuzzer drives.
    ///
    /// # Errors
    /// As [`CampaignFile::load`].
    pub fn from_toml_str(path: &Path, text: &str) -> Result<Self, PlanFileError> {
        let raw = crate::input::parse_toml::<RawCampaignFile>(path, text)?;
        Self::checked(path, raw, crate::input::sha256_hex(text.as_bytes()))
    }

    fn checked(path: &Path, raw: RawCampaignFile, sha256: String) -> Result<Self, PlanFileError> {
        let file = Self::resolve(path, raw, sha256)?;
        // The planner's own checks, mapped back to the TOML path of the activity at fault.
        planner::Instance::new(&file.problem).map_err(|e| file.planner_error(e))?;
        Ok(file)
    }

    /// A planner error with the TOML path of the activity or campaign it names.
    #[must_use]
    pub fn planner_error(&self, error: PlanError) -> PlanFileError {
        let activity_field = |id: &str, sub: &str| {
            self.problem
                .activities
                .iter()
                .position(|a| a.id == id)
                .map_or_else(
                    || "activities".to_string(),
                    |i| format!("{}{sub}", self.origins[i]),
                )
        };
        let campaign_field = |id: &str| {
            self.problem
                .campaigns
                .iter()
                .position(|c| c.id == id)
                .map_or_else(|| "campaigns".to_string(), |i| format!("campaigns[{i}]"))
        };
        let field = match &error {
            PlanError::InvalidProblem { .. } | PlanError::InvalidState { .. } => "sol".into(),
            PlanError::InvalidActivity { activity, .. }
            | PlanError::ImpossibleWindow { activity, .. }
            | PlanError::OutsideSol { activity, .. }
            | PlanError::PreconditionCycle { activity } => activity_field(activity, ""),
            PlanError::UnknownPrecondition { activity, .. } => {
                activity_field(activity, ".preconditions")
            }
            PlanError::UnknownCampaign { activity, .. } => activity_field(activity, ".campaign"),
            PlanError::InvalidLinkActivity {
                activity, field, ..
            } => match *field {
                "kind" => activity_field(activity, ".drive"),
                f => activity_field(activity, &format!(".{f}")),
            },
            PlanError::InvalidCampaign { campaign, .. } => campaign_field(campaign),
            PlanError::DuplicateId { field, .. } => (*field).to_string(),
            PlanError::TooManyTasks { .. } => "activities".into(),
        };
        PlanFileError::Planner {
            path: self.path.clone(),
            field,
            error,
        }
    }

    fn resolve(path: &Path, raw: RawCampaignFile, sha256: String) -> Result<Self, ScenarioError> {
        let c = FieldCheck { path };
        let s = &raw.sol;
        let start_s = c.lmst_s("sol.start_lmst", &s.start_lmst)?;
        let end_s = c.lmst_s("sol.end_lmst", &s.end_lmst)?;
        if end_s <= start_s {
            return Err(c.err(
                "sol.end_lmst",
                format!("a time after sol.start_lmst {:?}", s.start_lmst),
                format!("{:?}", s.end_lmst),
            ));
        }
        let cap = c.positive(
            "sol.battery_capacity_wh",
            s.battery_capacity_wh,
            "watt-hours",
        )?;
        let e0 = c.non_negative("sol.initial_energy_wh", s.initial_energy_wh, "watt-hours")?;
        if e0 > cap {
            return Err(c.err(
                "sol.initial_energy_wh",
                format!("at most sol.battery_capacity_wh = {cap} Wh"),
                e0,
            ));
        }
        let recharge_w = c.non_negative("sol.net_recharge_w", s.net_recharge_w, "watts")?;
        let data_cap = c.positive("sol.data_capacity_mb", s.data_capacity_mb, "megabytes")?;
        let d0 = c.non_negative(
            "sol.initial_data_mb",
            s.initial_data_mb.unwrap_or(0.0),
            "megabytes",
        )?;
        if d0 > data_cap {
            return Err(c.err(
                "sol.initial_data_mb",
                format!("at most sol.data_capacity_mb = {data_cap} MB"),
                d0,
            ));
        }
        let window = (start_s, end_s);

        // Campaign ids and goal-set members first: activities refer to both.
        let mut campaign_ids: HashMap<&str, usize> = HashMap::new();
        for (j, rc) in raw.campaigns.iter().enumerate() {
            c.id(&format!("campaigns[{j}].id"), &rc.id)?;
            if campaign_ids.insert(rc.id.as_str(), j).is_some() {
                return Err(c.err(
                    &format!("campaigns[{j}].id"),
                    "an id no other campaign uses",
                    format!("{:?}", rc.id),
                ));
            }
        }
        let activity_ids: HashMap<&str, usize> = raw
            .activities
            .iter()
            .enumerate()
            .map(|(i, a)| (a.id.as_str(), i))
            .collect();
        let mut member_of: HashMap<&str, &str> = HashMap::new();
        for (j, rc) in raw.campaigns.iter().enumerate() {
            for (k, m) in rc.members.iter().flatten().enumerate() {
                if !activity_ids.contains_key(m.as_str()) {
                    return Err(c.err(
                        &format!("campaigns[{j}].members[{k}]"),
                        "the id of an activity in [[activities]]",
                        format!("{m:?}"),
                    ));
                }
                if let Some(other) = member_of.insert(m.as_str(), rc.id.as_str())
                    && other != rc.id
                {
                    return Err(c.err(
                        &format!("campaigns[{j}].members[{k}]"),
                        format!("an activity not already a member of campaign {other:?}"),
                        format!("{m:?}"),
                    ));
                }
            }
        }

        let mut activities = Vec::new();
        let mut origins = Vec::new();
        let total_drive_m: f64;
        {
            let mut drive_m = 0.0;
            for a in &raw.activities {
                if let Some(d) = &a.drive
                    && d.length_m.is_finite()
                    && d.length_m > 0.0
                {
                    drive_m += d.length_m;
                }
            }
            total_drive_m = drive_m;
        }
        // State-based cadences split drives (when they give no split points of their own) so
        // a survey can run between segments.
        let state_every_m: Vec<f64> = raw
            .campaigns
            .iter()
            .filter(|rc| rc.intent == "state_based")
            .filter_map(|rc| rc.every_m.filter(|m| m.is_finite() && *m > 0.0))
            .collect();
        let all_ids: Vec<&str> = raw.activities.iter().map(|a| a.id.as_str()).collect();
        for (i, a) in raw.activities.iter().enumerate() {
            let f = format!("activities[{i}]");
            if all_ids[..i].contains(&a.id.as_str()) {
                return Err(c.err(
                    &format!("{f}.id"),
                    "an id no other activity uses",
                    format!("{:?}", a.id),
                ));
            }
            let mut act = activity(&c, &f, a, window, &state_every_m, &all_ids)?;
            let listed = member_of.get(a.id.as_str()).copied();
            match (&a.campaign, listed) {
                (Some(own), Some(l)) if own != l => {
                    return Err(c.err(
                        &format!("{f}.campaign"),
                        format!("{l:?} (campaign {l:?} lists it as a member)"),
                        format!("{own:?}"),
                    ));
                }
                (Some(own), _) => {
                    if !campaign_ids.contains_key(own.as_str()) {
                        return Err(c.err(
                            &format!("{f}.campaign"),
                            "the id of a campaign in [[campaigns]]",
                            format!("{own:?}"),
                        ));
                    }
                }
                (None, Some(l)) => act.campaign = Some(l.to_string()),
                (None, None) => {}
            }
            activities.push(act);
            origins.push(f);
        }

        let mut campaigns = Vec::new();
        for (j, rc) in raw.campaigns.iter().enumerate() {
            let f = format!("campaigns[{j}]");
            let (campaign, instances) = campaign(&c, &f, rc, window, total_drive_m, &activities)?;
            for inst in instances {
                if activities.iter().any(|o| o.id == inst.id) {
                    return Err(c.err(
                        &format!("{f}.template.id"),
                        format!(
                            "an id prefix whose instance ids do not clash with activity {:?}",
                            inst.id
                        ),
                        format!("{:?}", inst.id),
                    ));
                }
                activities.push(inst);
                origins.push(format!("{f}.template"));
            }
            campaigns.push(campaign);
        }
        // Counts only make sense against the members that exist.
        for (j, (cp, rc)) in campaigns.iter().zip(&raw.campaigns).enumerate() {
            let n = activities
                .iter()
                .filter(|a| a.campaign.as_deref() == Some(cp.id.as_str()))
                .count();
            if rc.min_count.is_some_and(|m| m > 0 && m as usize > n) {
                return Err(c.err(
                    &format!("campaigns[{j}].min_count"),
                    format!("at most the {n} member activities the campaign has"),
                    cp.min_count,
                ));
            }
        }

        c.text("name", &raw.name)?;
        c.text("description", &raw.description)?;
        let name = if raw.name.trim().is_empty() {
            // The file's name, printed as the plan's title: escaped like any input text.
            path.file_stem().map_or_else(
                || "campaign".into(),
                |s| maps::input_file::printable(&s.to_string_lossy()).into_owned(),
            )
        } else {
            raw.name.clone()
        };
        Ok(Self {
            path: path.to_path_buf(),
            name,
            description: raw.description,
            sha256,
            problem: Problem {
                start_s,
                end_s,
                battery_capacity_wh: cap,
                initial_energy_wh: e0,
                recharge_w,
                data_capacity_mb: data_cap,
                initial_data_mb: d0,
                activities,
                campaigns,
            },
            origins,
        })
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]
    use super::*;
    use planner::{Activity, ActivityKind};
    use sim::time::SolSeconds;

    fn resolve(text: &str) -> Result<CampaignFile, ScenarioError> {
        let raw: RawCampaignFile = toml::from_str(text).unwrap();
        CampaignFile::resolve(Path::new("t.toml"), raw, String::new())
    }

    const SOL: &str = "[sol]\nstart_lmst = \"09:00\"\nend_lmst = \"17:00\"\n\
        battery_capacity_wh = 100.0\ninitial_energy_wh = 50.0\nnet_recharge_w = 0.0\n\
        data_capacity_mb = 10.0\n";

    #[test]
    fn an_empty_sol_resolves_to_an_empty_problem() {
        let f = resolve(SOL).unwrap();
        assert!(f.problem.activities.is_empty() && f.problem.campaigns.is_empty());
        assert_eq!(f.name, "t");
        assert_eq!(
            f.problem.start_s,
            SolSeconds::parse_lmst("09:00").unwrap().planner_s()
        );
        planner::Instance::new(&f.problem).unwrap();
    }

    #[test]
    fn a_state_based_campaign_without_drives_has_no_instances() {
        let text = format!(
            "{SOL}[[campaigns]]\nid = \"s\"\nintent = \"state_based\"\nevery_m = 75.0\n\
             utility = 1.0\n[campaigns.template]\nduration_min = 5\npower_w = 1.0\n"
        );
        let f = resolve(&text).unwrap();
        assert!(f.problem.activities.is_empty());
        assert_eq!(f.problem.campaigns[0].max_count, 1);
    }

    #[test]
    fn periodic_windows_are_clipped_to_the_sol_and_drives_split_at_the_cadence() {
        let text = format!(
            "{SOL}[[activities]]\nid = \"d\"\ndrive = {{ length_m = 160.0, rate_m_per_h = 80.0 }}\n\
             power_w = 1.0\n\
             [[campaigns]]\nid = \"tau\"\nintent = \"periodic\"\nperiod_min = 180\n\
             tolerance_min = 20\nfirst_due_lmst = \"09:00\"\nutility = 1.0\n\
             [campaigns.template]\nduration_min = 5\npower_w = 1.0\n\
             [[campaigns]]\nid = \"s\"\nintent = \"state_based\"\nevery_m = 75.0\n\
             utility = 1.0\n[campaigns.template]\nduration_min = 5\npower_w = 1.0\n"
        );
        let f = resolve(&text).unwrap();
        let p = &f.problem;
        let ActivityKind::Drive(d) = &p.activities[0].kind else {
            panic!("drive expected")
        };
        assert_eq!(d.split_at_m, [75.0, 150.0]);
        assert_eq!(d.latest_end_s, None);
        let tau: Vec<&Activity> = p
            .activities
            .iter()
            .filter(|a| a.id.starts_with("tau-"))
            .collect();
        assert_eq!(tau[0].earliest_start_s, p.start_s);
        assert!(tau.iter().all(|a| a.latest_start_s + 300 <= p.end_s));
        assert_eq!(
            f.origins.last().map(String::as_str),
            Some("campaigns[1].template")
        );
        planner::Instance::new(p).unwrap();
    }

    #[test]
    fn a_drive_window_end_reaches_the_problem_and_is_checked() {
        let drive = |end: &str| {
            format!(
                "{SOL}[[activities]]\nid = \"d\"\npower_w = 1.0\n\
                 drive = {{ length_m = 100.0, rate_m_per_h = 100.0, latest_end_lmst = \"{end}\" }}\n"
            )
        };
        let f = resolve(&drive("14:00")).unwrap();
        let ActivityKind::Drive(d) = &f.problem.activities[0].kind else {
            panic!("drive expected")
        };
        assert_eq!(
            d.latest_end_s,
            Some(SolSeconds::parse_lmst("14:00").unwrap().planner_s())
        );
        let e = resolve(&drive("2pm")).unwrap_err().to_string();
        assert!(e.contains("activities[0].drive.latest_end_lmst"), "{e}");
        // An hour of driving cannot end by 09:30 in a window opening at 09:00.
        let f = resolve(&drive("09:30")).unwrap();
        let e = f.planner_error(planner::Instance::new(&f.problem).unwrap_err());
        assert!(e.to_string().contains("latest_end_s"), "{e}");
    }
}
