//! Issue 27: posing the shipped characters gives the same numbers, bit for bit, as before the
//! pose path was made lean (flat bone links, a fast `normal` world update, each constraint's
//! subtree listed once, each timeline's Bézier slots found once per pose).
//!
//! Every shipped character is posed — the setup pose, every clip at times going forward by
//! 1/60 s (past the end too), at times jumping back and forth (the cached key missed), with
//! targets moved, into one reused `Posed` and into fresh ones — and every bone's local and
//! world transform after every pose is folded into one digest. The digests were computed by
//! the code before the change (main at 8ed0511) and are frozen here: any change to any bit of
//! any pose fails this test. Applying the transform and path constraints changed spineboy's and
//! stretchyman's poses: their digests are those of that change (checked against Spine's runtime
//! by `reference_full.rs` in the edge).

use ikarus::character::{Character, PoseRequest, Posed};

fn read(file: &str) -> Character {
    let path = format!("{}/../../examples/characters/{file}", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).unwrap();
    ikarus_edge::character::load(&text, file).unwrap().character
}

/// FNV-1a over 64-bit words.
struct Digest(u64);

impl Digest {
    fn add(&mut self, v: f64) {
        for byte in v.to_bits().to_le_bytes() {
            self.0 = (self.0 ^ u64::from(byte)).wrapping_mul(0x0000_0100_0000_01b3);
        }
    }

    fn pose(&mut self, out: &Posed) {
        for i in 0..out.len() {
            let w = out.world(i);
            for v in [w.a, w.b, w.c, w.d, w.x, w.y] {
                self.add(v);
            }
            let l = out.local(i);
            for v in [l.x, l.y, l.rotation, l.scale_x, l.scale_y, l.shear_x, l.shear_y] {
                self.add(v);
            }
        }
    }
}

/// The digest of every pose of `c` described in the module's doc, and how many poses.
fn digest(c: &Character) -> (u64, usize) {
    let mut d = Digest(0xcbf2_9ce4_8422_2325);
    let mut poses = 0;
    let mut out = Posed::default();
    let mut pose = |request: &PoseRequest, out: &mut Posed, d: &mut Digest| {
        c.pose(request, out).unwrap();
        d.pose(out);
        poses += 1;
    };
    pose(&PoseRequest::default(), &mut out, &mut d);
    let targets: Vec<(usize, [f64; 2])> = c.ik_constraints().take(2).map(|(_, k)| (k.target, [30.0, -20.0])).collect();
    let last = c.bones().len() - 1;
    let far = [(last, [-45.0, 120.0])];
    for (k, clip) in c.clips().iter().enumerate() {
        let frames = (clip.duration * 60.0).ceil() as usize + 3;
        for i in 0..frames {
            let time = i as f64 / 60.0;
            pose(
                &PoseRequest { clip: Some((k, time)), targets: &[], bends: &[], turns: &[], skin: None },
                &mut out,
                &mut d,
            );
            pose(&PoseRequest::default(), &mut out, &mut d);
        }
        // Back and forth, so the cached key is missed both ways; a fresh `Posed` now and then.
        let mut x = 0.37f64;
        for i in 0..40 {
            x = (x * 3.7 + 0.123) % 1.0;
            let time = x * (clip.duration + 0.1) - 0.05;
            let request =
                PoseRequest { clip: Some((k, time.max(0.0))), targets: &[], bends: &[], turns: &[], skin: None };
            if i % 7 == 0 {
                pose(&request, &mut Posed::default(), &mut d);
            } else {
                pose(&request, &mut out, &mut d);
            }
            pose(
                &PoseRequest { clip: Some((k, time.max(0.0))), targets: &targets, bends: &[], turns: &[], skin: None },
                &mut out,
                &mut d,
            );
            pose(
                &PoseRequest { clip: Some((k, time.max(0.0))), targets: &far, bends: &[], turns: &[], skin: None },
                &mut out,
                &mut d,
            );
        }
    }
    pose(&PoseRequest { clip: None, targets: &targets, bends: &[], turns: &[], skin: None }, &mut out, &mut d);
    (d.0, poses)
}

#[test]
fn the_shipped_characters_pose_to_the_same_bits() {
    let want: [(&str, u64); 4] = [
        ("spine-spineboy-pro.json", 0xe231_6bc4_12c6_5888),
        ("spine-raptor-pro.json", 0xa0b3_f5a3_e482_055f),
        // Stretchyman: its transform and path constraints apply.
        ("spine-stretchyman-pro.json", 0x578f_6756_9730_91f7),
        ("dragonbones-mecha_1406_ske.json", 0x92a2_a4b3_fa42_f84f),
    ];
    let mut wrong = Vec::new();
    for (file, digest_want) in want {
        let (got, poses) = digest(&read(file));
        println!("{file}: {poses} poses, digest {got:#018x}");
        if got != digest_want {
            wrong.push(format!("{file}: {got:#018x}, want {digest_want:#018x}"));
        }
    }
    assert!(wrong.is_empty(), "{wrong:?}");
}
