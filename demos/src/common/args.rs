//! The demos' command line: `[FILE] [--frames N] [--screenshot F.png] [--bench]
//! [--size WxH]`.

use std::path::PathBuf;

use thiserror::Error;

/// Why the command line was refused.
#[derive(Debug, Error, PartialEq, Eq)]
#[non_exhaustive]
pub enum ArgsError {
    /// A flag that takes a value was last.
    #[error("{flag} needs a value")]
    MissingValue {
        /// The flag.
        flag: String,
    },
    /// A value did not parse.
    #[error("{flag} {value:?}: {reason}")]
    BadValue {
        /// The flag.
        flag: String,
        /// What was given.
        value: String,
        /// Why it is refused.
        reason: &'static str,
    },
    /// An unknown flag, or a second file.
    #[error(
        "unexpected argument {0:?} (usage: [FILE] [--frames N] [--screenshot F.png] [--bench] [--size WxH])"
    )]
    Unexpected(String),
}

/// What the command line asked for.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct RunArgs {
    /// The level (sandbox) or scene (viewer3d) file to open, if any.
    pub file: Option<PathBuf>,
    /// Run this many frames, then exit (after the screenshot, if one is asked for).
    pub frames: Option<u32>,
    /// Save the window's image here after the last frame.
    pub screenshot: Option<PathBuf>,
    /// Measure frame times and print them at exit.
    pub bench: bool,
    /// Inner window size in points.
    pub size: [u32; 2],
}

impl Default for RunArgs {
    fn default() -> Self {
        RunArgs {
            file: None,
            frames: None,
            screenshot: None,
            bench: false,
            size: [1280, 720],
        }
    }
}

/// Frames `--bench` runs when `--frames` is not given.
const BENCH_FRAMES: u32 = 300;

/// Frames a `--screenshot` without `--frames` waits before taking the image.
const SCREENSHOT_FRAMES: u32 = 10;

/// Largest window side accepted by `--size`.
const MAX_SIDE: u32 = 8192;

impl RunArgs {
    /// Parses the arguments after the program name.
    pub fn parse<I: IntoIterator<Item = String>>(args: I) -> Result<RunArgs, ArgsError> {
        let mut out = RunArgs::default();
        let mut args = args.into_iter();
        while let Some(arg) = args.next() {
            let mut value = |flag: &str| {
                args.next().ok_or_else(|| ArgsError::MissingValue {
                    flag: flag.to_string(),
                })
            };
            match arg.as_str() {
                "--frames" => out.frames = Some(parse_frames(&value("--frames")?)?),
                "--screenshot" => out.screenshot = Some(PathBuf::from(value("--screenshot")?)),
                "--bench" => out.bench = true,
                "--size" => out.size = parse_size(&value("--size")?)?,
                _ if arg.starts_with('-') => return Err(ArgsError::Unexpected(arg)),
                _ if out.file.is_some() => return Err(ArgsError::Unexpected(arg)),
                _ => out.file = Some(PathBuf::from(arg)),
            }
        }
        Ok(out)
    }

    /// Frames to run before exiting, if the run ends by itself.
    pub fn frame_limit(&self) -> Option<u32> {
        match (self.frames, self.bench, &self.screenshot) {
            (Some(n), _, _) => Some(n),
            (None, true, _) => Some(BENCH_FRAMES),
            (None, false, Some(_)) => Some(SCREENSHOT_FRAMES),
            (None, false, None) => None,
        }
    }
}

fn parse_frames(text: &str) -> Result<u32, ArgsError> {
    match text.parse::<u32>() {
        Ok(n) if (1..=1_000_000).contains(&n) => Ok(n),
        _ => Err(ArgsError::BadValue {
            flag: "--frames".into(),
            value: text.into(),
            reason: "must be a whole number from 1 to 1000000",
        }),
    }
}

fn parse_size(text: &str) -> Result<[u32; 2], ArgsError> {
    let bad = || ArgsError::BadValue {
        flag: "--size".into(),
        value: text.into(),
        reason: "must be WIDTHxHEIGHT, each from 64 to 8192",
    };
    let (w, h) = text.split_once('x').ok_or_else(bad)?;
    let side = |s: &str| {
        s.parse::<u32>()
            .ok()
            .filter(|v| (64..=MAX_SIDE).contains(v))
            .ok_or_else(bad)
    };
    Ok([side(w)?, side(h)?])
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(args: &[&str]) -> Result<RunArgs, ArgsError> {
        RunArgs::parse(args.iter().map(|s| s.to_string()))
    }

    #[test]
    fn flags_and_file_parse() {
        let a = parse(&[
            "level.ron",
            "--frames",
            "120",
            "--screenshot",
            "s.png",
            "--size",
            "640x360",
        ])
        .unwrap();
        assert_eq!(a.file, Some(PathBuf::from("level.ron")));
        assert_eq!(a.frames, Some(120));
        assert_eq!(a.screenshot, Some(PathBuf::from("s.png")));
        assert_eq!(a.size, [640, 360]);
        assert_eq!(a.frame_limit(), Some(120));
        assert_eq!(
            parse(&["--bench"]).unwrap().frame_limit(),
            Some(BENCH_FRAMES)
        );
        assert_eq!(parse(&[]).unwrap().frame_limit(), None);
    }

    #[test]
    fn bad_arguments_say_what_is_wrong() {
        assert!(matches!(
            parse(&["--frames"]),
            Err(ArgsError::MissingValue { .. })
        ));
        assert!(matches!(
            parse(&["--frames", "0"]),
            Err(ArgsError::BadValue { .. })
        ));
        assert!(matches!(
            parse(&["--frames", "-3"]),
            Err(ArgsError::BadValue { .. })
        ));
        assert!(matches!(
            parse(&["--size", "99999x10"]),
            Err(ArgsError::BadValue { .. })
        ));
        assert!(matches!(parse(&["a", "b"]), Err(ArgsError::Unexpected(_))));
        assert!(matches!(parse(&["--fly"]), Err(ArgsError::Unexpected(_))));
    }
}
