//! The job list: a pure function of the configuration. Jobs are ordered
//! town → configuration → weather → sequence → frame (the configuration's
//! list order), and every random choice derives from the master seed by
//! named streams, so any shard can compute any frame on its own.
//!
//! A sequence is one drive through its town (`drive_index`): dataset frame
//! `f` of a sequence is frame `f · stride` of its drive.

use std::path::PathBuf;

use super::config::DatasetConfig;
use crate::sampler::hash_words;
use crate::town::CameraConfig;
use crate::weather::Weather;

/// Stream tag of a town's seed (layout, buildings, traffic).
const TAG_TOWN: u64 = 0x5041_5254_4f57_4e00;
/// Stream tag of a sequence's weather draw.
const TAG_SEQUENCE: u64 = 0x5041_5253_4551_0000;
/// Stream tag of a frame's sample streams.
const TAG_FRAME: u64 = 0x5041_5246_5241_4d45;

/// One frame to render. Ordered by (town, configuration in DATASET.md order,
/// weather, sequence, frame).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Job {
    /// Town name.
    pub town: String,
    /// Camera configuration.
    pub config: CameraConfig,
    /// Weather preset.
    pub weather: Weather,
    /// Sequence index within (town, config, weather).
    pub sequence: u32,
    /// Frame index within the sequence (the file stem NNNNNN).
    pub frame: u32,
}

impl Job {
    fn key(&self) -> (&str, u64, Weather, u32, u32) {
        (
            &self.town,
            config_index(self.config),
            self.weather,
            self.sequence,
            self.frame,
        )
    }

    /// The identifier used in logs and verify reports:
    /// `town01/normal_clear/0000/000003`.
    pub fn id(&self) -> String {
        format!(
            "{}/{:06}",
            self.sequence_dir().to_string_lossy(),
            self.frame
        )
    }

    /// The sequence directory relative to the dataset root:
    /// `<town>/<config>_<weather>/<sequence:04>`.
    pub fn sequence_dir(&self) -> PathBuf {
        PathBuf::from(&self.town)
            .join(format!("{}_{}", self.config.name(), self.weather.name()))
            .join(sequence_name(self.sequence))
    }
}

impl Ord for Job {
    fn cmp(&self, other: &Self) -> std::cmp::Ordering {
        self.key().cmp(&other.key())
    }
}

impl PartialOrd for Job {
    fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}

/// Directory name of a sequence: 4-digit zero-padded index.
pub fn sequence_name(sequence: u32) -> String {
    format!("{sequence:04}")
}

/// FNV-1a of a name: turns town names into stream words.
fn name_word(name: &str) -> u64 {
    name.bytes().fold(0xcbf2_9ce4_8422_2325, |h, b| {
        (h ^ b as u64).wrapping_mul(0x100_0000_01b3)
    })
}

fn config_index(c: CameraConfig) -> u64 {
    crate::town::CONFIGS
        .iter()
        .position(|&x| x == c)
        .unwrap_or(0) as u64
}

/// Seed of a town's geometry and traffic: the same for every configuration,
/// weather and sequence of the dataset.
pub fn town_seed(seed: u64, town: &str) -> u64 {
    hash_words(&[seed, TAG_TOWN, name_word(town)])
}

/// Seed of a sequence's weather draw: one look per video, shared by every
/// configuration of the same drive.
pub fn sequence_seed(seed: u64, town: &str, weather: Weather, sequence: u32) -> u64 {
    hash_words(&[
        seed,
        TAG_SEQUENCE,
        name_word(town),
        weather as u64,
        sequence as u64,
    ])
}

/// Seed of a frame's sample streams.
pub fn frame_seed(seed: u64, job: &Job) -> u64 {
    hash_words(&[
        seed,
        TAG_FRAME,
        name_word(&job.town),
        config_index(job.config),
        job.weather as u64,
        job.sequence as u64,
        job.frame as u64,
    ])
}

/// The town frame of a job: its time step (at the town's fps) from the
/// start of its drive (`drive_index`).
pub fn town_frame(config: &DatasetConfig, job: &Job) -> u64 {
    job.frame as u64 * config.stride as u64
}

/// The drive of a job's sequence (`parallax render --town T --sequence N`):
/// a counter over the (configuration, weather, sequence) of a town,
/// `(c · 7 + w) · sequences + s` with c the configuration's index in
/// DATASET.md order (0..6), w the weather's in `Weather::ALL` (0..7), s
/// the sequence, so no two sequences of a town share a drive. The town's
/// seed (`town_seed`) carries the master seed and the town.
pub fn drive_index(config: &DatasetConfig, job: &Job) -> u64 {
    let w = Weather::ALL
        .iter()
        .position(|&x| x == job.weather)
        .unwrap_or(0) as u64;
    let c = config_index(job.config) * Weather::ALL.len() as u64 + w;
    c * config.sequences as u64 + job.sequence as u64
}

/// Every job of the configuration in the stable order.
pub fn plan(config: &DatasetConfig) -> Vec<Job> {
    let configs = config.camera_configs();
    let weathers = config.weather_list();
    let mut jobs = Vec::with_capacity(frame_count(config) as usize);
    for town in &config.towns {
        for &c in &configs {
            for &w in &weathers {
                for sequence in 0..config.sequences {
                    for frame in 0..config.frames_per_sequence {
                        jobs.push(Job {
                            town: town.clone(),
                            config: c,
                            weather: w,
                            sequence,
                            frame,
                        });
                    }
                }
            }
        }
    }
    jobs
}

/// Number of jobs without listing them.
pub fn frame_count(config: &DatasetConfig) -> u64 {
    [
        config.towns.len() as u64,
        config.configs.len() as u64,
        config.weathers.len() as u64,
        config.sequences as u64,
        config.frames_per_sequence as u64,
    ]
    .iter()
    .product()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn job(town: &str, config: CameraConfig, weather: Weather, sequence: u32, frame: u32) -> Job {
        Job {
            town: town.into(),
            config,
            weather,
            sequence,
            frame,
        }
    }

    #[test]
    fn every_sequence_of_a_town_gets_its_own_drive_and_frames_count_from_its_start() {
        let c = super::super::presets::stereocarla();
        let mut drives = std::collections::BTreeMap::new();
        for j in plan(&c).iter().filter(|j| j.frame == 0) {
            let d = drive_index(&c, j);
            let key = (j.config, j.weather, j.sequence);
            assert_eq!(
                *drives.entry((j.town.clone(), d)).or_insert(key),
                key,
                "{j:?}"
            );
        }
        // Per town: the 6 × 7 × 7 sequences take drives 0..294, each once.
        for town in &c.towns {
            let d: Vec<u64> = drives
                .keys()
                .filter(|k| &k.0 == town)
                .map(|k| k.1)
                .collect();
            assert_eq!(d, (0..294).collect::<Vec<u64>>(), "{town}");
        }
        let j = job("town01", CameraConfig::Roll15, Weather::Night, 1, 3);
        assert_eq!(drive_index(&c, &j), (2 * 7 + 4) * 7 + 1);
        assert_eq!(town_frame(&c, &j), 3 * c.stride as u64);
    }

    #[test]
    fn plan_is_stable_ordered_and_counted() {
        let c = super::super::presets::demo();
        let a = plan(&c);
        assert_eq!(a, plan(&c));
        assert_eq!(a.len() as u64, frame_count(&c));
        // 1 town × 6 configurations × 2 weathers × 1 sequence × 2 frames.
        assert_eq!(a.len(), 6 * 2 * 2);
        assert_eq!(a[0].id(), "town01/normal_clear/0000/000000");
        assert_eq!(a[1].id(), "town01/normal_clear/0000/000001");
        assert_eq!(a[2].id(), "town01/normal_sunset/0000/000000");
        // The promised order (town, configuration, weather, sequence, frame):
        // strictly increasing over the whole plan, hence also no duplicates.
        assert!(a.windows(2).all(|w| w[0] < w[1]));
        // A plan with every axis longer than one: nested in that order,
        // frame fastest, then sequence, weather, configuration, town.
        let mut c = super::super::presets::demo();
        c.towns = vec!["town01".into(), "town02".into()];
        c.sequences = 3;
        c.frames_per_sequence = 2;
        let b = plan(&c);
        assert_eq!(b.len() as u64, frame_count(&c));
        assert_eq!(b.len(), 2 * 6 * 2 * 3 * 2);
        assert!(b.windows(2).all(|w| w[0] < w[1]));
        let configs = c.camera_configs();
        for (k, j) in b.iter().enumerate() {
            let (frame, r) = (k % 2, k / 2);
            let (sequence, r) = (r % 3, r / 3);
            let (weather, r) = (r % 2, r / 2);
            let (config, town) = (r % 6, r / 6);
            let want = job(
                ["town01", "town02"][town],
                configs[config],
                [Weather::Clear, Weather::Sunset][weather],
                sequence as u32,
                frame as u32,
            );
            assert_eq!(*j, want, "job {k}");
        }
    }

    #[test]
    fn seeds_differ_per_axis_and_repeat_per_key() {
        let base = job("town01", CameraConfig::Normal, Weather::Clear, 1, 3);
        let other_config = crate::town::CONFIGS
            .iter()
            .copied()
            .find(|&x| x != CameraConfig::Normal)
            .expect("a second configuration");
        // Jobs differing from `base` in exactly one field.
        let variants = [
            job("town02", CameraConfig::Normal, Weather::Clear, 1, 3),
            job("town01", other_config, Weather::Clear, 1, 3),
            job("town01", CameraConfig::Normal, Weather::Sunset, 1, 3),
            job("town01", CameraConfig::Normal, Weather::Clear, 2, 3),
            job("town01", CameraConfig::Normal, Weather::Clear, 1, 4),
        ];
        for v in &variants {
            assert_ne!(frame_seed(7, &base), frame_seed(7, v), "{v:?}");
        }
        assert_ne!(frame_seed(7, &base), frame_seed(8, &base));
        // Every job of a plan with two towns, configurations, weathers,
        // sequences and frames gets its own frame seed.
        let mut c = super::super::presets::demo();
        c.towns = vec!["town01".into(), "town02".into()];
        c.sequences = 3;
        let jobs = plan(&c);
        let seeds: std::collections::BTreeSet<u64> =
            jobs.iter().map(|j| frame_seed(c.seed, j)).collect();
        assert_eq!(seeds.len(), jobs.len());
        // Town seeds: per town and master seed.
        assert_ne!(town_seed(7, "town01"), town_seed(7, "town02"));
        assert_ne!(town_seed(7, "town01"), town_seed(8, "town01"));
        // Sequence seeds: per town, weather, sequence and master seed.
        let s = sequence_seed(7, "town01", Weather::Clear, 0);
        assert_ne!(s, sequence_seed(7, "town02", Weather::Clear, 0));
        assert_ne!(s, sequence_seed(7, "town01", Weather::Sunset, 0));
        assert_ne!(s, sequence_seed(7, "town01", Weather::Clear, 1));
        assert_ne!(s, sequence_seed(8, "town01", Weather::Clear, 0));
        // The streams are tagged apart: over the plan above no town seed is
        // a sequence seed or a frame seed, and no sequence seed a frame seed.
        let towns: std::collections::BTreeSet<u64> =
            jobs.iter().map(|j| town_seed(c.seed, &j.town)).collect();
        let sequences: std::collections::BTreeSet<u64> = jobs
            .iter()
            .map(|j| sequence_seed(c.seed, &j.town, j.weather, j.sequence))
            .collect();
        assert_eq!((towns.len(), sequences.len()), (2, 2 * 2 * 3));
        assert!(towns.is_disjoint(&sequences) && towns.is_disjoint(&seeds));
        assert!(sequences.is_disjoint(&seeds));
    }
}
