//! The atlas reader on the four shipped atlases, Spine 3.x spellings, several pages and bad lines.

use super::*;

fn art(name: &str) -> String {
    let path = format!("{}/../../examples/characters/{name}.atlas", env!("CARGO_MANIFEST_DIR"));
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"))
}

#[test]
fn the_shipped_atlases_read_with_their_counts_and_regions() {
    for (name, count, size, rotated) in [
        ("spineboy", 40, [1024, 256], 10),
        ("raptor", 38, [1024, 512], 13),
        ("stretchyman", 5, [1024, 256], 5),
        ("celestial-circus", 67, [1024, 1024], 35),
    ] {
        let text = art(name);
        let a = read(&text).unwrap();
        assert_eq!(a.pages.len(), 1, "{name}");
        assert_eq!(a.pages[0].file, format!("{name}.png"));
        assert_eq!(a.pages[0].size, size, "{name}");
        assert!(!a.pages[0].pma);
        assert_eq!(a.regions.len(), count, "{name}");
        // `grep -c "rotate: 90"` on each file.
        assert_eq!(a.regions.iter().filter(|r| r.degrees == 90).count(), rotated, "{name}");
    }
    let boy = read(&art("spineboy")).unwrap();
    assert_eq!(boy.pages[0].scale, [0.5, 0.5]);
    // crosshair: bounds 352, 7, 45, 45 (not rotated, no whitespace).
    let r = &boy.regions[0];
    assert_eq!((r.name.as_str(), r.page, r.bounds, r.degrees), ("crosshair", 0, [352.0, 7.0, 45.0, 45.0], 0));
    assert_eq!((r.offsets, r.original, r.page_size), ([0.0, 0.0], [45.0, 45.0], [1024.0, 256.0]));
    // front-fist-open: bounds 710, 51, 43, 44, rotate: 90.
    let r = boy.regions.iter().find(|r| r.name == "front-fist-open").unwrap();
    assert_eq!((r.bounds, r.degrees, r.original), ([710.0, 51.0, 43.0, 44.0], 90, [43.0, 44.0]));
    assert_eq!(boy.lookup().index("front-fist-open").map(|i| &boy.regions[i].name), Some(&r.name));
    // stretchyman's body: 2, 104, 141, 452 rotated: on the page it takes 452 × 141.
    let man = read(&art("stretchyman")).unwrap();
    let body = man.regions.iter().find(|r| r.name == "body").unwrap();
    assert_eq!((body.bounds, body.degrees), ([2.0, 104.0, 141.0, 452.0], 90));
}

#[test]
fn spine_3_spellings_several_pages_and_whitespace_read() {
    let text = "\none.png\nsize: 64,32\nformat: RGBA8888\nfilter: Linear,Linear\nrepeat: none\nhead\n  rotate: true\n  xy: 2, 3\n  size: 10, 20\n  orig: 14, 26\n  offset: 1, 2\n  index: -1\n\ntwo.png\n  size: 128, 128\n  pma: true\n  scale: 0.5, 0.25\nhand\n  bounds: 4, 5, 6, 7\n  offsets: 1, 1, 9, 9\n  rotate: 270\n  index: 3\n  split: 1, 2, 3, 4\n";
    let a = read(text).unwrap();
    assert_eq!(a.pages.len(), 2);
    assert_eq!(
        (a.pages[1].file.as_str(), a.pages[1].size, a.pages[1].pma, a.pages[1].scale),
        ("two.png", [128, 128], true, [0.5, 0.25])
    );
    let head = &a.regions[0];
    assert_eq!(
        (head.page, head.bounds, head.offsets, head.original, head.degrees, head.pma),
        (0, [2.0, 3.0, 10.0, 20.0], [1.0, 2.0], [14.0, 26.0], 90, false)
    );
    let hand = &a.regions[1];
    assert_eq!(
        (hand.page, hand.bounds, hand.offsets, hand.original, hand.degrees, hand.pma),
        (1, [4.0, 5.0, 6.0, 7.0], [1.0, 1.0], [9.0, 9.0], 270, true)
    );
    assert_eq!(a.indices, [-1, 3]);
    // A region name that is also a page's image name is still a region inside a page.
    assert_eq!(read("p.png\nsize: 8, 8\nq.png\nbounds: 0, 0, 1, 1\n").unwrap().regions[0].name, "q.png");
}

#[test]
fn bad_lines_are_refused_with_their_number_field_and_value() {
    for (text, error) in [
        ("size: 3, 3\n", "atlas line 1: size: \"3, 3\": a setting before any page's image name"),
        ("p.png\nsize: 3\n", "atlas line 2: size: \"3\": expected 2 numbers, got 1"),
        ("p.png\nsize: 0, 4\n", "atlas line 2: size: \"0, 4\": expected two whole numbers of pixels, 1 to 65536"),
        ("p.png\nsize: 8, 8\npma: yes\n", "atlas line 3: pma: \"yes\": expected true or false"),
        (
            "p.png\nsize: 8, 8\nwidth: 3\n",
            "atlas line 3: width: \"3\": not a page setting (size, format, filter, repeat, pma, scale)",
        ),
        ("p.png\nsize: 8, 8\na\nbounds: 0, 0, x, 1\n", "atlas line 4: bounds: \"0, 0, x, 1\": \"x\" is not a number"),
        (
            "p.png\nsize: 8, 8\na\nrotate: 45\n",
            "atlas line 4: rotate: \"45\": expected true, false or a multiple of 90 degrees",
        ),
        ("p.png\nsize: 8, 8\na\nindex: one\n", "atlas line 4: index: \"one\": expected a whole number"),
        ("p.png\nsize: 8, 8\na\nrotate: 90\n", "atlas line 3 (region \"a\"): bounds: missing"),
        (
            "p.png\nsize: 8, 8\na\nbounds: 4, 0, 5, 2\n",
            "atlas line 3 (region \"a\"): bounds: 4, 0, 5, 2: not within the page (8 × 8)",
        ),
        (
            "p.png\nsize: 8, 8\na\nbounds: 0, 0, 2, 9\nrotate: 90\n",
            "atlas line 3 (region \"a\"): bounds: 0, 0, 2, 9: not within the page (8 × 8)",
        ),
        (
            "p.png\nsize: 8, 8\na\nbounds: 0, 0, 4, 4\noffsets: 1, 0, 4, 4\n",
            "atlas line 3 (region \"a\"): offsets: 1, 0, 4, 4: the packed image (4 × 4) must fit in the original size",
        ),
        (
            "p.png\na\nbounds: 0, 0, 1, 1\n",
            "atlas line 2 (region \"a\"): page \"p.png\" has no size: (needed to place its regions)",
        ),
    ] {
        assert_eq!(read(text).unwrap_err(), error, "{text:?}");
    }
}
