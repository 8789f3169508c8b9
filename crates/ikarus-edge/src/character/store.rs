//! Characters read once and referred to by id: `/api/rig/parse` of a character file keeps what
//! it read here and answers its id; later requests (`/api/pose`, `/api/animate`, `/api/track`,
//! `/api/render`) give `"character": ID` instead of the file's text, so playback sends a few
//! hundred bytes a frame instead of the whole file (287 kB for spineboy) and the file is not
//! read again for every frame.
//!
//! One store a process ([`global`]): the server's, the WebAssembly module's, Python's. It is
//! bounded: at most [`MAX_CHARACTERS`] characters and [`MAX_TEXT_BYTES`] bytes of their files'
//! text; past either, the least recently used are let go. An id that is not (or no longer)
//! here is refused naming the field, and the caller sends the file again.
//!
//! The id is the text's content hash (64-bit FNV-1a) and its length: the same file gets the
//! same id, so sending it again costs one read and no second copy. The hash is not
//! cryptographic: two different files of one id would replace each other, which only the one
//! who sends both can arrange, and which costs them nothing but their own character.

use std::sync::{Arc, Mutex, OnceLock};

use super::Loaded;

/// Most characters kept.
pub const MAX_CHARACTERS: usize = 8;

/// Most bytes of file text kept, over every character.
pub const MAX_TEXT_BYTES: usize = 64 << 20;

/// A character kept: what reading its file gave, and the file's text (a Spine export adds to
/// it).
#[derive(Debug)]
pub struct Stored {
    /// The character read.
    pub loaded: Loaded,
    /// The file's text as it was sent.
    pub text: String,
}

/// The characters kept, least recently used first.
#[derive(Debug, Default)]
pub struct Store {
    kept: Mutex<Vec<(String, Arc<Stored>)>>,
}

/// The process's store.
pub fn global() -> &'static Store {
    static STORE: OnceLock<Store> = OnceLock::new();
    STORE.get_or_init(Store::default)
}

/// The id of a file's text: its FNV-1a hash and length, in hex (`c` and 24 digits).
#[must_use]
pub fn id_of(text: &str) -> String {
    let mut hash: u64 = 0xcbf2_9ce4_8422_2325;
    for &b in text.as_bytes() {
        hash ^= u64::from(b);
        hash = hash.wrapping_mul(0x0100_0000_01b3);
    }
    format!("c{hash:016x}{:08x}", text.len() as u32)
}

impl Store {
    /// Keeps `loaded`, read from `text`, and answers its id (a character of the same id is
    /// replaced), letting the least recently used go past the bounds.
    pub fn put(&self, text: String, loaded: Loaded) -> (String, Arc<Stored>) {
        let id = id_of(&text);
        let stored = Arc::new(Stored { loaded, text });
        let mut kept = self.kept.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        kept.retain(|(k, _)| *k != id);
        kept.push((id.clone(), Arc::clone(&stored)));
        let mut bytes: usize = kept.iter().map(|(_, s)| s.text.len()).sum();
        while kept.len() > 1 && (kept.len() > MAX_CHARACTERS || bytes > MAX_TEXT_BYTES) {
            bytes -= kept[0].1.text.len();
            kept.remove(0);
        }
        (id, stored)
    }

    /// The character of `id`, now the most recently used; `None` when it is not kept.
    pub fn get(&self, id: &str) -> Option<Arc<Stored>> {
        let mut kept = self.kept.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        let at = kept.iter().position(|(k, _)| k == id)?;
        let entry = kept.remove(at);
        let stored = Arc::clone(&entry.1);
        kept.push(entry);
        Some(stored)
    }

    /// How many characters are kept.
    pub fn len(&self) -> usize {
        self.kept.lock().unwrap_or_else(std::sync::PoisonError::into_inner).len()
    }

    /// Whether none is kept.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const SPINEBOY: &str = include_str!("../../../../examples/characters/spine-spineboy-pro.json");

    #[test]
    fn a_kept_character_is_found_by_its_id_and_the_oldest_goes_first() {
        let store = Store::default();
        let loaded = super::super::load(SPINEBOY, "spineboy").unwrap();
        let (id, _) = store.put(SPINEBOY.to_owned(), loaded.clone());
        assert_eq!(id, id_of(SPINEBOY));
        assert_eq!(store.get(&id).unwrap().loaded.character.bones().len(), 67);
        assert!(store.get("c0000").is_none());
        // The same text again: the same id, one entry.
        store.put(SPINEBOY.to_owned(), loaded.clone());
        assert_eq!(store.len(), 1);
        // Past the count, the least recently used goes.
        let texts: Vec<String> = (0..MAX_CHARACTERS).map(|i| format!("{SPINEBOY}{}", " ".repeat(i + 1))).collect();
        for t in &texts {
            store.put(t.clone(), loaded.clone());
        }
        assert_eq!(store.len(), MAX_CHARACTERS);
        assert!(store.get(&id).is_none(), "the oldest was let go");
        assert!(store.get(&id_of(&texts[0])).is_some());
    }
}
