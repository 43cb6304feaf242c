//! Levels as Bevy assets: `.ron` level files loaded by the asset server and validated by the
//! library, so that a bad level is an asset load failure naming the node and the reason.

use bevy::asset::io::Reader;
use bevy::asset::{Asset, AssetLoader, LoadContext};
use bevy::reflect::TypePath;
use craterfield::field2d::{Level, LevelError, MAX_LEVEL_BYTES};
use thiserror::Error;

/// A level loaded by the asset server (`asset_server.load("levels/default.ron")`).
#[derive(Asset, TypePath, Debug, Clone)]
pub struct LevelAsset {
    /// The validated level.
    pub level: Level,
}

/// Why a level asset did not load.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum LevelLoadError {
    /// The asset could not be read.
    #[error("cannot read the level: {0}")]
    Io(#[from] std::io::Error),
    /// The file is larger than the level parser accepts (read no further than the limit).
    #[error("the level file is over the limit of {limit} bytes")]
    TooLarge {
        /// The limit, [`MAX_LEVEL_BYTES`].
        limit: usize,
    },
    /// The text is not UTF-8.
    #[error("the level file is not UTF-8 text: {0}")]
    NotText(#[from] std::str::Utf8Error),
    /// The library refused the level: the message names the node path and the reason.
    #[error("{0}")]
    Level(#[from] LevelError),
}

/// Loads `.ron` levels (and `.level.ron`) into [`LevelAsset`]s.
#[derive(Default, TypePath)]
pub struct LevelLoader;

impl AssetLoader for LevelLoader {
    type Asset = LevelAsset;
    type Settings = ();
    type Error = LevelLoadError;

    async fn load(
        &self,
        reader: &mut dyn Reader,
        _settings: &(),
        _load_context: &mut LoadContext<'_>,
    ) -> Result<LevelAsset, LevelLoadError> {
        let bytes = read_bounded(reader, MAX_LEVEL_BYTES).await?;
        let level = level_from_bytes(&bytes)?;
        Ok(LevelAsset { level })
    }

    fn extensions(&self) -> &[&str] {
        &["level.ron", "ron"]
    }
}

/// Reads at most `limit` bytes: a file past the limit is refused without being held whole.
async fn read_bounded(reader: &mut dyn Reader, limit: usize) -> Result<Vec<u8>, LevelLoadError> {
    use bevy::tasks::futures_lite::AsyncReadExt;
    let mut bytes = Vec::new();
    let mut chunk = [0u8; 16 * 1024];
    loop {
        let n = reader.read(&mut chunk).await?;
        if n == 0 {
            return Ok(bytes);
        }
        if bytes.len() + n > limit {
            return Err(LevelLoadError::TooLarge { limit });
        }
        bytes.extend_from_slice(&chunk[..n]);
    }
}

/// Parses and validates a level file's bytes, as the loader does.
pub fn level_from_bytes(bytes: &[u8]) -> Result<Level, LevelLoadError> {
    if bytes.len() > MAX_LEVEL_BYTES {
        return Err(LevelLoadError::TooLarge {
            limit: MAX_LEVEL_BYTES,
        });
    }
    Ok(Level::from_ron(std::str::from_utf8(bytes)?)?)
}
