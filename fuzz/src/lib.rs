//! What the fuzz targets share: the checksum fix-up (so mutated files and messages reach
//! past the CRC check into the decoders) and a small level to apply events to.

use craterfield::field2d::Level;

/// Overwrites the trailing CRC-32 of a file or message with the checksum of the bytes
/// before it, as every format of `craterfield::net` stores it.
pub fn fix_crc(bytes: &mut [u8]) {
    if bytes.len() >= 4 {
        let n = bytes.len() - 4;
        let crc = craterfield::net::crc32(&bytes[..n]);
        bytes[n..].copy_from_slice(&crc.to_le_bytes());
    }
}

/// A small level (two islands over ground), quick to build a terrain of.
pub fn small_level() -> Level {
    Level::from_ron(
        r#"Level(name: "fuzz", bounds: (min: (0.0, 0.0), max: (1024.0, 512.0)),
            materials: [(name: "soil", color: (1, 2, 3)), (name: "rock", color: (4, 5, 6))],
            spawns: [(100.0, 400.0), (900.0, 400.0), (500.0, 450.0), (300.0, 450.0)],
            root: Union([
                HalfPlane(point: (0.0, 120.0), normal: (0.0, 1.0)),
                Material(id: 1, node: Circle(center: (300.0, 250.0), radius: 60.0)),
                Circle(center: (700.0, 220.0), radius: 40.0),
            ]))"#,
    )
    .expect("the fuzz level is valid")
}
