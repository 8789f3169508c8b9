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

/// What a kept thing costs the store: the bytes counted against its bound.
pub trait Weigh {
    /// The bytes it holds, as the store counts them.
    fn bytes(&self) -> usize;
}

impl Weigh for Stored {
    fn bytes(&self) -> usize {
        self.text.len()
    }
}

/// Things kept by id, least recently used first, at most `most` of them and `bytes` bytes
/// ([`Weigh`]) over all.
#[derive(Debug)]
pub struct Store<T = Stored> {
    kept: Mutex<Vec<(String, Arc<T>)>>,
    most: usize,
    bytes: usize,
}

impl Default for Store<Stored> {
    /// The characters' bounds: [`MAX_CHARACTERS`], [`MAX_TEXT_BYTES`].
    fn default() -> Self {
        Self::new(MAX_CHARACTERS, MAX_TEXT_BYTES)
    }
}

/// The process's store of characters.
pub fn global() -> &'static Store {
    static STORE: OnceLock<Store> = OnceLock::new();
    STORE.get_or_init(Store::default)
}

/// The id of a file's text: its FNV-1a hash and length, in hex (`c` and 24 digits).
#[must_use]
pub fn id_of(text: &str) -> String {
    format!("c{:016x}{:08x}", fnv(FNV_START, text.as_bytes()), text.len() as u32)
}

/// `tag` and the FNV-1a hash and total length of `parts`, each part followed by a separator
/// byte (moving bytes from one part to the next changes the id), in hex: the id of a thing made
/// of several files (an atlas and its page images).
#[must_use]
pub fn hashed(tag: char, parts: &[&[u8]]) -> String {
    let hash = parts.iter().fold(FNV_START, |h, part| fnv(fnv(h, part), &[0xff]));
    let len: usize = parts.iter().map(|p| p.len()).sum();
    format!("{tag}{hash:016x}{:08x}", len as u32)
}

const FNV_START: u64 = 0xcbf2_9ce4_8422_2325;

/// FNV-1a of `bytes` from `hash`.
fn fnv(hash: u64, bytes: &[u8]) -> u64 {
    bytes.iter().fold(hash, |h, &b| (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3))
}

impl<T: Weigh> Store<T> {
    /// An empty store keeping at most `most` things and `bytes` bytes of them.
    #[must_use]
    pub fn new(most: usize, bytes: usize) -> Self {
        Self { kept: Mutex::new(Vec::new()), most, bytes }
    }

    /// Keeps `thing` under `id` (a thing of the same id is replaced), letting the least
    /// recently used go past the bounds (never the one just kept).
    pub fn keep(&self, id: String, thing: T) -> Arc<T> {
        let thing = Arc::new(thing);
        let mut kept = self.kept.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        kept.retain(|(k, _)| *k != id);
        kept.push((id, Arc::clone(&thing)));
        let mut bytes: usize = kept.iter().map(|(_, s)| s.bytes()).sum();
        while kept.len() > 1 && (kept.len() > self.most || bytes > self.bytes) {
            bytes -= kept[0].1.bytes();
            kept.remove(0);
        }
        thing
    }

    /// The thing of `id`, now the most recently used; `None` when it is not kept.
    pub fn get(&self, id: &str) -> Option<Arc<T>> {
        let mut kept = self.kept.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        let at = kept.iter().position(|(k, _)| k == id)?;
        let entry = kept.remove(at);
        let stored = Arc::clone(&entry.1);
        kept.push(entry);
        Some(stored)
    }

    /// How many things are kept.
    pub fn len(&self) -> usize {
        self.kept.lock().unwrap_or_else(std::sync::PoisonError::into_inner).len()
    }

    /// Whether none is kept.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
}

impl Store<Stored> {
    /// Keeps `loaded`, read from `text`, and answers its id ([`id_of`]).
    pub fn put(&self, text: String, loaded: Loaded) -> (String, Arc<Stored>) {
        let id = id_of(&text);
        let stored = self.keep(id.clone(), Stored { loaded, text });
        (id, stored)
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
