//! What a character's messages say: names quoted, escaped and cut (one line whatever a file
//! names its bones and animations), an IK file's limits in degrees under its own field, the GIF
//! cap naming the flags a character's motion has, and a Spine atlas given as a rig told for what
//! it is.

mod common;

use common::{SPINEBOY, fails, ikarus, stderr, stdout, temp_file};
use serde_json::json;

const RAPTOR: &str = "../../examples/characters/spine-raptor-pro.json";
const ATLAS_TEXT: &str =
    "raptor.png\n\tsize: 1024, 512\n\tfilter: Linear, Linear\n\tscale: 0.5\nback-arm\n\tbounds: 895, 295, 46, 25\n";
const ATLAS: &str =
    "this is a Spine texture atlas (.atlas), not a skeleton: pass the skeleton's .json (or .skel) exported beside it";

/// A character whose bone and animation names hold a line break and a terminal escape.
fn hostile() -> String {
    json!({
        "skeleton": {"spine": "4.2.0"},
        "bones": [{"name": "root"}, {"name": "leg\n\u{1b}[2J", "parent": "root", "length": 10}],
        "animations": {"walk\n\u{1b}[2J": {}}
    })
    .to_string()
}

#[test]
fn names_are_quoted_and_escaped_in_errors_and_in_the_text_table() {
    let path = temp_file("messages", "hostile.json", &hostile());
    // Before: the list of animations and the table printed the name raw, over two lines, with
    // the escape that clears the terminal.
    let e = fails(&["pose", "--rig", &path, "--animation", "run"], 2);
    assert_eq!(
        e,
        format!(
            "ikarus: rig file {path}: animation \"run\": no such animation (the file has: \"walk\\n\\u{{1b}}[2J\")\n"
        )
    );
    let o = ikarus(&["pose", "--rig", &path, "--format", "text"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = stdout(&o);
    assert!(!text.contains('\u{1b}'), "{text:?}");
    assert_eq!(text.lines().count(), 3, "a header and one line per bone: {text:?}");
    assert!(text.lines().nth(2).unwrap().starts_with("\"leg\\n\\u{1b}[2J\"  "), "{text:?}");
    // A version line on stderr, too, cut (it was printed whole).
    let version = format!("9\n\u{1b}[2J{}", "x".repeat(100));
    let odd = json!({"skeleton": {"spine": version}, "bones": [{"name": "root"}]}).to_string();
    let odd = temp_file("messages", "version.json", &odd);
    let o = ikarus(&["pose", "--rig", &odd, "--format", "json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(
        stderr(&o),
        format!(
            "ikarus: rig file {odd}: skeleton.spine: \"9\\n\\u{{1b}}[2J{}…\" (106 bytes) is not a version ikarus was made for (3.8, 4.0 to 4.2); read as 4.2\n",
            "x".repeat(58)
        )
    );
    // A keyed bone that is not there, named by the user, is quoted too.
    let e = fails(&["animate", "--rig", &path, "--target", "toe\u{1b}[2J=1,1"], 2);
    assert_eq!(e, format!("ikarus: rig file {path}: target \"toe\\u{{1b}}[2J\": no bone of that name\n"));
}

#[test]
fn a_long_name_is_cut_in_a_message() {
    // Before: a name used twice was printed whole (a 30 MB name, a 30 MB line).
    let name = "x".repeat(1 << 20);
    let text = json!({"skeleton": {"spine": "4.2.0"}, "bones": [{"name": name}, {"name": name}]}).to_string();
    let path = temp_file("messages", "long.json", &text);
    let e = fails(&["pose", "--rig", &path], 2);
    assert_eq!(
        e,
        format!(
            "ikarus: rig file {path}: bones[1].name = \"{}…\" (1048576 bytes): also the name of bones[0]\n",
            "x".repeat(64)
        )
    );
}

/// The last line `ikarus ARGS` writes to stderr, after checking it exits with 2 (spineboy's
/// own line about the constraints ikarus leaves inactive comes first).
fn last_error(args: &[&str]) -> String {
    let o = ikarus(args);
    assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
    stderr(&o).lines().last().unwrap().to_owned()
}

#[test]
fn an_ik_files_limits_are_told_in_degrees_under_its_own_field() {
    // Before: the limits came out in radians (`bone "front-shin": limits: min must not exceed
    // max, got [0.17453292519943295, -0.17453292519943295]`), and limits of 1e308 degrees
    // reached the solver, refused as the character file's `goal "front-shin".bend`.
    let ik = temp_file("messages", "legs.ik.toml", "[bones.front-shin]\nlimits_deg = [10.0, -10.0]\n");
    assert_eq!(
        last_error(&["pose", "--rig", SPINEBOY, "--ik", "ikarus", "--ik-file", &ik]),
        format!(
            "ikarus: ik file {ik}: bones.front-shin.limits_deg = [10, -10]: the lower limit must not exceed the upper (degrees)"
        )
    );
    let ik = temp_file("messages", "far.ik.toml", "[bones.front-shin]\nlimits_deg = [1e308, 1e308]\n");
    assert_eq!(
        last_error(&["pose", "--rig", SPINEBOY, "--ik", "ikarus", "--ik-file", &ik]),
        format!(
            "ikarus: ik file {ik}: bones.front-shin.limits_deg = [1e308, 1e308]: each limit must be within -360 and 360 degrees"
        )
    );
}

/// Valid limits that leave no angle on the side the shin's IK constraint bends it to: before,
/// refused as the solver's `goal "front-shin".bend`; now as the IK rules' field.
#[test]
fn limits_that_leave_the_bend_no_room_name_the_ik_files_field_not_a_goal() {
    let ik = temp_file("messages", "room.ik.toml", "[bones.front-shin]\nlimits_deg = [5.0, 10.0]\n");
    let e = last_error(&[
        "pose",
        "--rig",
        SPINEBOY,
        "--target",
        "front-leg-target=60,60",
        "--ik",
        "ikarus",
        "--ik-file",
        &ik,
    ]);
    assert!(
        e.ends_with(
            "bones.front-shin.limits_deg: the IK rules' limits of bone \"front-shin\" leave no angle on the side its IK constraint bends it to (bendPositive): widen them, or bend the other way"
        ),
        "{e}"
    );
    assert!(!e.contains("goal"), "{e}");
}

#[test]
fn over_the_gif_cap_a_character_is_told_the_flags_it_has() {
    // Before: "fewer --frames", a flag a character's motion does not have; and every frame was
    // posed before the cap was looked at.
    let gif = temp_file("messages", "m.gif", "");
    let e = fails(&["animate", "--rig", RAPTOR, "--target", "root=1,1", "--duration", "100", "--out", &gif], 2);
    assert_eq!(
        e,
        "ikarus: --out: a GIF of 3001 frames of 800×800 is 1920640000 pixels, more than the cap of 1000000000 (a lower \
         --fps or a shorter --duration, a smaller --width/--height, or raise it with --max-gif-pixels N)\n"
    );
    let e = fails(
        &["track", "--rig", RAPTOR, "--effector", "root", "--line", "0,0,1,1", "--samples", "5000", "--out", &gif],
        2,
    );
    assert!(e.contains("(fewer --samples, a smaller --width/--height, or raise it with --max-gif-pixels N)"), "{e}");
    assert!(!e.contains("--frames"), "{e}");
}

#[test]
fn a_spine_atlas_given_as_a_rig_is_told_for_what_it_is() {
    // Before: `line 2, column 1: expected `.`, `=`` from the TOML parser.
    let path = temp_file("messages", "raptor.atlas", ATLAS_TEXT);
    for args in [
        vec!["pose", "--rig", &path],
        vec!["solve", "--rig", &path, "--goal", "a=1,1"],
        vec!["animate", "--rig", &path, "--target", "a=1,1"],
        vec!["track", "--rig", &path, "--effector", "a", "--line", "0,0,1,1"],
    ] {
        assert_eq!(fails(&args, 2), format!("ikarus: rig file {path}: {ATLAS}\n"), "{args:?}");
    }
    let s = common::server::start(&[]);
    let a = s.post_raw("/api/rig/parse", "application/toml", ATLAS_TEXT.as_bytes());
    assert_eq!(a.status, 200);
    assert_eq!(a.json(), json!({"problem": format!("rig file: {ATLAS}")}));
    assert_eq!(s.post("/api/pose", &json!({"rig": ATLAS_TEXT})).error(422), format!("rig: {ATLAS}"));
}
