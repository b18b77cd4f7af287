//! Checkpoints of long sweeps: a JSON header and named arrays (`.npy`), written so that a
//! run killed at any instant leaves a complete earlier checkpoint or none.
//!
//! A checkpoint is a *generation*: its arrays are written first, each atomically and with
//! the generation in its file name, then the header (`checkpoint.json`, naming the
//! generation) replaces the previous header atomically, and only then are the previous
//! generation's arrays deleted. Reading follows the header, so it always sees one whole
//! generation.

use std::path::{Path, PathBuf};

use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};

const HEADER: &str = "checkpoint.json";

#[derive(Serialize, Deserialize)]
struct Header<M> {
    generation: u64,
    arrays: Vec<String>,
    meta: M,
}

/// A directory holding one sweep's checkpoints.
#[derive(Debug, Clone)]
pub struct Checkpoints {
    dir: PathBuf,
    generation: u64,
}

/// An array to store: `f64`, `u16` or `u8` values.
pub enum Array<'a> {
    /// Doubles.
    F64(&'a [f64]),
    /// 16-bit counters.
    U16(&'a [u16]),
    /// Bytes (flags).
    U8(&'a [u8]),
}

impl Checkpoints {
    /// Checkpoints in `dir` (created on first save).
    pub fn new(dir: &Path) -> Self {
        Self {
            dir: dir.to_path_buf(),
            generation: 0,
        }
    }

    fn array_path(&self, generation: u64, name: &str) -> PathBuf {
        self.dir.join(format!("{name}.{generation}.npy"))
    }

    /// Saves `meta` and `arrays` as the next generation.
    pub fn save<M: Serialize>(&mut self, meta: &M, arrays: &[(&str, Array)]) -> Result<()> {
        std::fs::create_dir_all(&self.dir).map_err(|e| Error::io(&self.dir, e))?;
        let previous = self.read_header::<serde_json::Value>().ok();
        let generation = previous.as_ref().map_or(0, |h| h.generation) + 1;
        for (name, array) in arrays {
            let path = self.array_path(generation, name);
            crate::io::write_atomic_with(&path, |w| write_npy(w, array))?;
        }
        let header = Header {
            generation,
            arrays: arrays.iter().map(|(n, _)| n.to_string()).collect(),
            meta,
        };
        let bytes = serde_json::to_vec(&header).expect("checkpoint headers serialise");
        crate::io::write_atomic(&self.dir.join(HEADER), &bytes)?;
        if let Some(prev) = previous {
            for name in prev.arrays {
                let _ = std::fs::remove_file(self.array_path(prev.generation, &name));
            }
        }
        self.generation = generation;
        Ok(())
    }

    fn read_header<M: DeserializeOwned>(&self) -> Result<Header<M>> {
        let path = self.dir.join(HEADER);
        let bytes = std::fs::read(&path).map_err(|e| Error::io(&path, e))?;
        serde_json::from_slice(&bytes).map_err(|e| Error::bad_file(&path, e.to_string()))
    }

    /// The last checkpoint's metadata, if there is a readable one.
    pub fn load_meta<M: DeserializeOwned>(&mut self) -> Option<M> {
        let h = self.read_header::<M>().ok()?;
        self.generation = h.generation;
        Some(h.meta)
    }

    /// An `f64` array of the last loaded checkpoint.
    pub fn load_f64(&self, name: &str) -> Result<Vec<f64>> {
        read_npy(&self.array_path(self.generation, name))
    }

    /// A `u16` array of the last loaded checkpoint.
    pub fn load_u16(&self, name: &str) -> Result<Vec<u16>> {
        read_npy(&self.array_path(self.generation, name))
    }

    /// A `u8` array of the last loaded checkpoint.
    pub fn load_u8(&self, name: &str) -> Result<Vec<u8>> {
        read_npy(&self.array_path(self.generation, name))
    }

    /// Removes every checkpoint (after the sweep's result is safely stored).
    pub fn clear(&self) {
        let _ = std::fs::remove_dir_all(&self.dir);
    }
}

fn write_npy<W: std::io::Write>(w: &mut W, array: &Array) -> std::io::Result<()> {
    use npyz::WriterBuilder;
    fn put<T: npyz::AutoSerialize + Copy, W: std::io::Write>(
        w: &mut W,
        v: &[T],
    ) -> std::io::Result<()> {
        let mut writer = npyz::WriteOptions::<T>::new()
            .default_dtype()
            .shape(&[v.len() as u64])
            .writer(w)
            .begin_nd()?;
        writer.extend(v.iter().copied())?;
        writer.finish()
    }
    match array {
        Array::F64(v) => put(w, v),
        Array::U16(v) => put(w, v),
        Array::U8(v) => put(w, v),
    }
}

fn read_npy<T: npyz::Deserialize>(path: &Path) -> Result<Vec<T>> {
    let bytes = std::fs::read(path).map_err(|e| Error::io(path, e))?;
    let npy = npyz::NpyFile::new(&bytes[..]).map_err(|e| Error::bad_file(path, e.to_string()))?;
    npy.into_vec()
        .map_err(|e| Error::bad_file(path, e.to_string()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn save_load_and_replace_generations() {
        let dir = tempfile::tempdir().unwrap();
        let mut c = Checkpoints::new(&dir.path().join("ck"));
        assert!(c.load_meta::<u32>().is_none());
        c.save(
            &7u32,
            &[("a", Array::F64(&[1.0, 2.5])), ("b", Array::U16(&[3, 4]))],
        )
        .unwrap();
        c.save(&8u32, &[("a", Array::F64(&[9.0])), ("b", Array::U16(&[5]))])
            .unwrap();
        let mut r = Checkpoints::new(&dir.path().join("ck"));
        assert_eq!(r.load_meta::<u32>(), Some(8));
        assert_eq!(r.load_f64("a").unwrap(), vec![9.0]);
        assert_eq!(r.load_u16("b").unwrap(), vec![5]);
        // Only the live generation's arrays remain.
        assert_eq!(std::fs::read_dir(dir.path().join("ck")).unwrap().count(), 3);
        r.clear();
        assert!(!dir.path().join("ck").exists());
    }

    #[test]
    fn a_save_cut_short_leaves_the_previous_generation_whole() {
        let dir = tempfile::tempdir().unwrap();
        let ck = dir.path().join("ck");
        let mut c = Checkpoints::new(&ck);
        c.save(
            &1u32,
            &[("a", Array::F64(&[1.0; 4])), ("b", Array::U8(&[1; 4]))],
        )
        .unwrap();
        // Killed while saving generation 2, between the array writes and the header: `a`
        // written (same file name and path as `save` uses), `b` half-written (a temporary
        // never renamed), the header still naming generation 1.
        crate::io::write_atomic_with(&c.array_path(2, "a"), |w| {
            write_npy(w, &Array::F64(&[2.0; 4]))
        })
        .unwrap();
        std::fs::write(ck.join("b.2.npy.tmp.4294967295.0"), b"\x93NUMPY\x01\x00v").unwrap();
        let mut r = Checkpoints::new(&ck);
        assert_eq!(r.load_meta::<u32>(), Some(1));
        assert_eq!(r.load_f64("a").unwrap(), vec![1.0; 4]);
        assert_eq!(r.load_u8("b").unwrap(), vec![1; 4]);

        // The resumed sweep saves over the debris, and readers follow the new header.
        r.save(
            &2u32,
            &[("a", Array::F64(&[3.0; 4])), ("b", Array::U8(&[3; 4]))],
        )
        .unwrap();
        let mut r = Checkpoints::new(&ck);
        assert_eq!(r.load_meta::<u32>(), Some(2));
        assert_eq!(r.load_f64("a").unwrap(), vec![3.0; 4]);
        assert_eq!(r.load_u8("b").unwrap(), vec![3; 4]);

        // Killed after the header, before the previous arrays were deleted: the reader
        // sees the new generation.
        let stale = c.array_path(2, "a");
        let copy = ck.join("stale.npy");
        std::fs::copy(&stale, &copy).unwrap();
        r.save(
            &3u32,
            &[("a", Array::F64(&[4.0; 4])), ("b", Array::U8(&[4; 4]))],
        )
        .unwrap();
        std::fs::rename(&copy, &stale).unwrap();
        let mut r = Checkpoints::new(&ck);
        assert_eq!(r.load_meta::<u32>(), Some(3));
        assert_eq!(r.load_f64("a").unwrap(), vec![4.0; 4]);
    }
}
