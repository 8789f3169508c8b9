//! `ikarus bench --characters`: every shipped character (`examples/characters/`) posed as its
//! runtime poses it (the default `--ik runtime`, every constraint kind active), one thread, into
//! one reused `Posed` per kind of pose: the setup pose with its constraints, and an animation
//! (its row's clip) at a time that advances by [`STEP`] each pose, wrapping at the clip's
//! duration — for a character with physics constraints, one frame of a game's loop
//! (`Character::play_frame`: the physics stepping from the frame before, as a game calls it
//! every frame). The two kinds alternate pose by pose, so that both see the same load; each pose
//! is timed alone, and the medians and 99th percentiles are reported.

use std::io::{self, Write};
use std::time::Instant;

use ikarus::character::{Character, PlayFrame, PoseRequest, Posed};
use ikarus_edge::error::Error;
use serde::Serialize;

use super::{BenchArgs, Sink};

/// The shipped characters, by file name, with their text and the clip each is animated by.
const CHARACTERS: [(&str, &str, &str); 5] = [
    ("spine-spineboy-pro.json", include_str!("../../../examples/characters/spine-spineboy-pro.json"), "walk"),
    ("spine-raptor-pro.json", include_str!("../../../examples/characters/spine-raptor-pro.json"), "walk"),
    ("spine-stretchyman-pro.json", include_str!("../../../examples/characters/spine-stretchyman-pro.json"), "sneak"),
    (
        "spine-celestial-circus-pro.json",
        include_str!("../../../examples/characters/spine-celestial-circus-pro.json"),
        "swing",
    ),
    (
        "dragonbones-mecha_1406_ske.json",
        include_str!("../../../examples/characters/dragonbones-mecha_1406_ske.json"),
        "walk",
    ),
];

/// How far the animation's time advances from one pose to the next, seconds (a frame at 60 Hz).
pub const STEP: f64 = 1.0 / 60.0;

/// Untimed poses of each kind before the timed ones.
const WARMUP: usize = 100;

/// One character's row.
#[derive(Debug, Clone, Serialize)]
pub struct CharacterRow {
    /// The file's name in `examples/characters/`.
    pub file: &'static str,
    /// How many bones.
    pub bones: usize,
    /// The animation posed (one frame of a game's play with physics, for a character that has
    /// physics constraints), if the character has it.
    pub clip: Option<String>,
    /// Median µs of the setup pose with its constraints.
    pub pose_us: f64,
    /// 99th percentile µs of the setup pose with its constraints.
    pub pose_p99_us: f64,
    /// Median µs of a pose with the animation sampled (none without an animation).
    pub animated_pose_us: Option<f64>,
    /// 99th percentile µs of the animated pose (of the setup pose without an animation).
    pub p99_us: f64,
}

/// What the output says about the run as a whole.
#[derive(Debug, Clone, Serialize)]
pub struct CharactersHeader {
    /// The command line.
    pub command: String,
    /// This program's version.
    pub ikarus_version: &'static str,
    /// Timed poses of each kind per character.
    pub poses: usize,
    /// Untimed poses of each kind first.
    pub warmup_poses: usize,
    /// Seconds the animation advances per pose.
    pub step_s: f64,
    /// Whose rules the constraints follow.
    pub ik: &'static str,
    /// Threads (one).
    pub threads: usize,
    /// The machine's CPUs.
    pub cpus: usize,
    /// `/proc/loadavg`'s three load averages when the run ended, where there is one.
    pub loadavg: Option<String>,
    /// Whether this is a debug build (its times mean little).
    pub debug_build: bool,
}

#[derive(Serialize)]
struct Report {
    header: CharactersHeader,
    characters: Vec<CharacterRow>,
}

/// Runs `ikarus bench --characters`.
pub fn run(args: &BenchArgs, sink: &dyn Sink) -> Result<(), Error> {
    let poses = args.poses as usize;
    let mut characters = Vec::new();
    for (file, text, clip) in CHARACTERS {
        let loaded = ikarus_edge::character::load(text, file)?;
        characters.push(measure(file, &loaded.character, loaded.character.clip_index(clip), poses)?);
    }
    let header = CharactersHeader {
        command: super::command_line(),
        ikarus_version: env!("CARGO_PKG_VERSION"),
        poses,
        warmup_poses: WARMUP,
        step_s: STEP,
        ik: "runtime",
        threads: 1,
        cpus: std::thread::available_parallelism().map_or(1, usize::from),
        loadavg: loadavg(),
        debug_build: cfg!(debug_assertions),
    };
    let report = Report { header, characters };
    sink.stdout(&mut |w| {
        if args.json {
            serde_json::to_writer_pretty(&mut *w, &report)?;
            writeln!(w)
        } else {
            table(w, &report, args.markdown)
        }
    })
}

/// Times `poses` setup poses and `poses` animated ones (game frames with physics), alternating.
fn measure(file: &'static str, c: &Character, clip: Option<usize>, poses: usize) -> Result<CharacterRow, Error> {
    let physics = c.constraints().iter().any(|k| k.kind() == "physics");
    let duration = clip.map_or(0.0, |k| c.clips()[k].duration);
    let (mut setup_out, mut animated_out) = (Posed::default(), Posed::default());
    let (mut setup, mut animated) = (Vec::with_capacity(poses), Vec::with_capacity(poses));
    let fail = |e: ikarus::character::PoseError| Error::runtime(format!("{file}: {e}"));
    for i in 0..WARMUP + poses {
        let start = Instant::now();
        c.pose(&PoseRequest::default(), &mut setup_out).map_err(fail)?;
        let t = start.elapsed().as_secs_f64() * 1e6;
        if i >= WARMUP {
            setup.push(t);
        }
        if let Some(k) = clip {
            let clock = i as f64 * STEP;
            let time = if duration > 0.0 { clock % duration } else { 0.0 };
            let request = PoseRequest { clip: Some((k, time)), ..PoseRequest::default() };
            let frame =
                PlayFrame { clock, before: i.checked_sub(1).map(|j| j as f64 * STEP), world: c.physics_world() };
            let start = Instant::now();
            if physics {
                c.play_frame(&request, &frame, &mut animated_out).map_err(fail)?;
            } else {
                c.pose(&request, &mut animated_out).map_err(fail)?;
            }
            let t = start.elapsed().as_secs_f64() * 1e6;
            if i >= WARMUP {
                animated.push(t);
            }
        }
    }
    let (pose_us, pose_p99_us) = median_p99(&mut setup);
    let animated_pose = (!animated.is_empty()).then(|| median_p99(&mut animated));
    Ok(CharacterRow {
        file,
        bones: c.bones().len(),
        clip: clip.map(|k| c.clips()[k].name.clone()),
        pose_us,
        pose_p99_us,
        animated_pose_us: animated_pose.map(|a| a.0),
        p99_us: animated_pose.map_or(pose_p99_us, |a| a.1),
    })
}

/// The median and the 99th percentile (the nearest rank) of `times`, which is sorted.
fn median_p99(times: &mut [f64]) -> (f64, f64) {
    times.sort_by(f64::total_cmp);
    let n = times.len();
    let rank = |q: f64| times[((q * n as f64).ceil() as usize).clamp(1, n) - 1];
    (rank(0.5), rank(0.99))
}

/// `/proc/loadavg`'s first three fields, where the file exists.
fn loadavg() -> Option<String> {
    let text = std::fs::read_to_string("/proc/loadavg").ok()?;
    Some(text.split_whitespace().take(3).collect::<Vec<_>>().join(" "))
}

/// The rows as an aligned text table or a Markdown one, headed by the run's facts.
fn table(w: &mut dyn Write, r: &Report, markdown: bool) -> io::Result<()> {
    let h = &r.header;
    let facts = format!(
        "{} poses of each kind per character after {} untimed, the animation advancing {:.4} s per pose, \
         --ik {}, one thread, load average {}{}",
        h.poses,
        h.warmup_poses,
        h.step_s,
        h.ik,
        h.loadavg.as_deref().unwrap_or("unknown"),
        if h.debug_build { " (a debug build: times mean little)" } else { "" }
    );
    let head = ["file", "bones", "clip", "pose µs", "pose p99 µs", "animated µs", "animated p99 µs"];
    let us = |v: f64| format!("{v:.2}");
    let rows: Vec<[String; 7]> = r
        .characters
        .iter()
        .map(|c| {
            let animated = c.animated_pose_us.is_some();
            [
                c.file.to_owned(),
                c.bones.to_string(),
                c.clip.clone().unwrap_or_else(|| "-".to_owned()),
                us(c.pose_us),
                us(c.pose_p99_us),
                c.animated_pose_us.map_or_else(|| "-".to_owned(), us),
                if animated { us(c.p99_us) } else { "-".to_owned() },
            ]
        })
        .collect();
    if markdown {
        writeln!(w, "`{}`: {facts}", h.command)?;
        writeln!(w)?;
        writeln!(w, "| {} |", head.join(" | "))?;
        writeln!(w, "| --- | ---: | --- | ---: | ---: | ---: | ---: |")?;
        for row in &rows {
            writeln!(w, "| {} |", row.join(" | "))?;
        }
        return Ok(());
    }
    writeln!(w, "ikarus bench --characters: {facts}")?;
    writeln!(w)?;
    let mut widths = head.map(|s| s.chars().count());
    for row in &rows {
        for (width, cell) in widths.iter_mut().zip(row) {
            *width = (*width).max(cell.chars().count());
        }
    }
    let head = head.map(str::to_owned);
    for row in std::iter::once(&head).chain(&rows) {
        let mut line = String::from(" ");
        for (k, (cell, &width)) in row.iter().zip(&widths).enumerate() {
            let pad = " ".repeat(width - cell.chars().count());
            line += "  ";
            line += &if k == 0 || k == 2 { format!("{cell}{pad}") } else { format!("{pad}{cell}") };
        }
        writeln!(w, "{}", line.trim_end())?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_median_and_p99_are_nearest_ranks() {
        let mut t: Vec<f64> = (1..=200).rev().map(f64::from).collect();
        assert_eq!(median_p99(&mut t), (100.0, 198.0));
        assert_eq!(median_p99(&mut [3.0]), (3.0, 3.0));
    }

    #[test]
    fn every_shipped_character_is_read_and_has_its_clip() {
        for (file, text, clip) in CHARACTERS {
            let c = ikarus_edge::character::load(text, file).unwrap().character;
            assert!(c.clip_index(clip).is_some(), "{file} has no {clip}");
        }
    }
}
