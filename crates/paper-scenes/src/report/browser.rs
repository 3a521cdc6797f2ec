//! Headless Chromium for a report: the DOM it parsed (`--dump-dom`) and screenshots, with the
//! flags a closed network needs (no background networking, component updates or sync) and a
//! fresh profile per run.
//!
//! Chromium is found at `$HANDSTACK_CHROMIUM` (set by `cargo xtask test`), else
//! `/usr/bin/chromium` (Debian's package), else `chromium` on `PATH`.

use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// The flags every run gets: headless, no sandbox (root in CI), and nothing that reaches out
/// to the network.
pub const FLAGS: [&str; 8] = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-quic",
    "--no-first-run",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
];

/// How long one Chromium run may take before it is killed.
pub const TIMEOUT: Duration = Duration::from_secs(120);

/// What can go wrong driving the browser or reading its screenshot.
#[derive(Debug, thiserror::Error)]
pub enum BrowserError {
    /// No Chromium executable was found.
    #[error(
        "no Chromium: set HANDSTACK_CHROMIUM, or run `cargo xtask test` (which installs Debian's \
         `chromium` when it can), or `apt-get install chromium`"
    )]
    NotFound,
    /// Chromium could not be started.
    #[error(
        "starting Chromium at {path}: {source} (set HANDSTACK_CHROMIUM to a Chromium, or run \
         `cargo xtask test`, which installs Debian's `chromium` when it can)"
    )]
    Start {
        /// The executable.
        path: PathBuf,
        /// Why.
        source: std::io::Error,
    },
    /// Chromium ran past [`TIMEOUT`] and was killed.
    #[error("chromium did not finish within {0:?}")]
    Timeout(Duration),
    /// Chromium exited unsuccessfully or wrote nothing.
    #[error("chromium failed ({status}): {stderr_tail}")]
    Failed {
        /// Its exit status.
        status: String,
        /// The last lines it wrote to stderr.
        stderr_tail: String,
    },
    /// A file could not be read or written.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        source: std::io::Error,
    },
    /// A screenshot is not a PNG we can read or write.
    #[error("{path}: PNG: {message}")]
    Png {
        /// The file.
        path: PathBuf,
        /// The decoder's or encoder's message.
        message: String,
    },
}

/// A Chromium executable.
#[derive(Debug, Clone)]
pub struct Chromium {
    path: PathBuf,
}

impl Chromium {
    /// Finds Chromium (see the module docs), or [`BrowserError::NotFound`].
    pub fn find() -> Result<Self, BrowserError> {
        if let Some(p) = std::env::var_os("HANDSTACK_CHROMIUM").filter(|p| !p.is_empty()) {
            return Ok(Self { path: p.into() });
        }
        let debian = Path::new("/usr/bin/chromium");
        if debian.exists() {
            return Ok(Self {
                path: debian.into(),
            });
        }
        std::env::var_os("PATH")
            .into_iter()
            .flat_map(|p| std::env::split_paths(&p).collect::<Vec<_>>())
            .map(|dir| dir.join("chromium"))
            .find(|p| p.is_file())
            .map(|path| Self { path })
            .ok_or(BrowserError::NotFound)
    }

    /// The executable's path.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The DOM Chromium built from the HTML file `page`, serialised (`--dump-dom`). `scratch`
    /// holds the run's fresh profile.
    pub fn dump_dom(&self, page: &Path, scratch: &Path) -> Result<String, BrowserError> {
        let out = self.run(&["--dump-dom".to_owned()], page, scratch)?;
        if out.trim().is_empty() {
            return Err(BrowserError::Failed {
                status: "exit 0".into(),
                stderr_tail: "--dump-dom printed nothing".into(),
            });
        }
        Ok(out)
    }

    /// A `width × height` screenshot of the HTML file `page`, written to `png`.
    pub fn screenshot(
        &self,
        page: &Path,
        png: &Path,
        (width, height): (u32, u32),
        scratch: &Path,
    ) -> Result<(), BrowserError> {
        let _ = std::fs::remove_file(png);
        self.run(
            &[
                format!("--screenshot={}", absolute(png)?.display()),
                format!("--window-size={width},{height}"),
                "--hide-scrollbars".to_owned(),
            ],
            page,
            scratch,
        )?;
        if !png.exists() {
            return Err(BrowserError::Failed {
                status: "exit 0".into(),
                stderr_tail: format!("no screenshot at {}", png.display()),
            });
        }
        Ok(())
    }

    /// A screenshot of the whole page, `width` wide: taken `max_height` tall, then cut below
    /// the last row that differs from the page background (plus a margin). Returns its size.
    pub fn full_page_screenshot(
        &self,
        page: &Path,
        png: &Path,
        width: u32,
        max_height: u32,
        scratch: &Path,
    ) -> Result<(u32, u32), BrowserError> {
        self.screenshot(page, png, (width, max_height), scratch)?;
        let mut image = Image::read(png)?;
        image.crop_background_rows(24);
        image.write(png)?;
        Ok((image.width, image.height))
    }

    /// Runs Chromium on `page` with [`FLAGS`], `extra` and a fresh profile under `scratch`;
    /// returns its stdout.
    fn run(&self, extra: &[String], page: &Path, scratch: &Path) -> Result<String, BrowserError> {
        let profile = scratch.join(format!("chromium-profile-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&profile);
        std::fs::create_dir_all(&profile).map_err(|source| BrowserError::Io {
            path: profile.clone(),
            source,
        })?;
        let url = format!("file://{}", absolute(page)?.display());
        let mut child = Command::new(&self.path)
            .args(FLAGS)
            .arg(format!("--user-data-dir={}", profile.display()))
            .args(extra)
            .arg(url)
            .stdin(Stdio::null())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .map_err(|source| BrowserError::Start {
                path: self.path.clone(),
                source,
            })?;
        // Drain both pipes on threads so a large DOM never blocks the browser.
        let drain = |pipe: Option<Box<dyn Read + Send>>| {
            std::thread::spawn(move || {
                let mut s = String::new();
                if let Some(mut p) = pipe {
                    let _ = p.read_to_string(&mut s);
                }
                s
            })
        };
        let stdout = drain(child.stdout.take().map(|p| Box::new(p) as _));
        let stderr = drain(child.stderr.take().map(|p| Box::new(p) as _));
        let start = Instant::now();
        let status = loop {
            match child.try_wait() {
                Ok(Some(status)) => break status,
                Ok(None) if start.elapsed() > TIMEOUT => {
                    let _ = child.kill();
                    let _ = child.wait();
                    let _ = std::fs::remove_dir_all(&profile);
                    return Err(BrowserError::Timeout(TIMEOUT));
                }
                // A bounded poll of the child's exit, not a wait for an event.
                Ok(None) => std::thread::sleep(Duration::from_millis(20)),
                Err(source) => {
                    return Err(BrowserError::Io {
                        path: self.path.clone(),
                        source,
                    });
                }
            }
        };
        let out = stdout.join().unwrap_or_default();
        let err = stderr.join().unwrap_or_default();
        let _ = std::fs::remove_dir_all(&profile);
        if !status.success() {
            let lines: Vec<&str> = err.lines().collect();
            return Err(BrowserError::Failed {
                status: status.to_string(),
                stderr_tail: lines[lines.len().saturating_sub(8)..].join("\n"),
            });
        }
        Ok(out)
    }
}

fn absolute(path: &Path) -> Result<PathBuf, BrowserError> {
    std::path::absolute(path).map_err(|source| BrowserError::Io {
        path: path.to_path_buf(),
        source,
    })
}

/// An 8-bit RGBA image read from (or written to) a PNG.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Image {
    /// Width, pixels.
    pub width: u32,
    /// Height, pixels.
    pub height: u32,
    /// Row-major RGBA bytes.
    pub rgba: Vec<u8>,
}

impl Image {
    /// Decodes the PNG at `path` (any bit depth / colour type, converted to 8-bit RGBA).
    pub fn read(path: &Path) -> Result<Self, BrowserError> {
        let png_err = |message: String| BrowserError::Png {
            path: path.to_path_buf(),
            message,
        };
        let file = std::fs::File::open(path).map_err(|source| BrowserError::Io {
            path: path.to_path_buf(),
            source,
        })?;
        let mut decoder = png::Decoder::new(std::io::BufReader::new(file));
        decoder.set_transformations(png::Transformations::normalize_to_color8());
        let mut reader = decoder.read_info().map_err(|e| png_err(e.to_string()))?;
        let mut buf = vec![0; reader.output_buffer_size()];
        let info = reader
            .next_frame(&mut buf)
            .map_err(|e| png_err(e.to_string()))?;
        let pixels = &buf[..info.buffer_size()];
        let rgba: Vec<u8> = match info.color_type {
            png::ColorType::Rgba => pixels.to_vec(),
            png::ColorType::Rgb => pixels
                .chunks_exact(3)
                .flat_map(|p| [p[0], p[1], p[2], 255])
                .collect(),
            png::ColorType::GrayscaleAlpha => pixels
                .chunks_exact(2)
                .flat_map(|p| [p[0], p[0], p[0], p[1]])
                .collect(),
            png::ColorType::Grayscale => pixels.iter().flat_map(|&g| [g, g, g, 255]).collect(),
            png::ColorType::Indexed => {
                return Err(png_err("indexed colour left after expansion".into()));
            }
        };
        Ok(Self {
            width: info.width,
            height: info.height,
            rgba,
        })
    }

    /// Encodes the image as an RGBA PNG at `path`.
    pub fn write(&self, path: &Path) -> Result<(), BrowserError> {
        let png_err = |message: String| BrowserError::Png {
            path: path.to_path_buf(),
            message,
        };
        let file = std::fs::File::create(path).map_err(|source| BrowserError::Io {
            path: path.to_path_buf(),
            source,
        })?;
        let mut encoder = png::Encoder::new(std::io::BufWriter::new(file), self.width, self.height);
        encoder.set_color(png::ColorType::Rgba);
        encoder.set_depth(png::BitDepth::Eight);
        encoder.set_compression(png::Compression::Best);
        let mut writer = encoder.write_header().map_err(|e| png_err(e.to_string()))?;
        writer
            .write_image_data(&self.rgba)
            .map_err(|e| png_err(e.to_string()))?;
        writer.finish().map_err(|e| png_err(e.to_string()))
    }

    /// How many distinct RGBA colours the image holds (a blank page has one).
    ///
    /// ```
    /// use paper_scenes::report::browser::Image;
    /// let white_and_red = Image { width: 2, height: 1, rgba: vec![255, 255, 255, 255, 255, 0, 0, 255] };
    /// assert_eq!(white_and_red.distinct_colours(), 2);
    /// ```
    pub fn distinct_colours(&self) -> usize {
        let mut seen: Vec<u32> = self
            .rgba
            .chunks_exact(4)
            .map(|p| u32::from_be_bytes([p[0], p[1], p[2], p[3]]))
            .collect();
        seen.sort_unstable();
        seen.dedup();
        seen.len()
    }

    /// Cuts the rows below the last one that differs from the bottom-left pixel (the page
    /// background), keeping `margin` background rows.
    pub fn crop_background_rows(&mut self, margin: u32) {
        let row_bytes = 4 * self.width as usize;
        if row_bytes == 0 || self.rgba.len() < row_bytes {
            return;
        }
        let bg: [u8; 4] = self.rgba[self.rgba.len() - row_bytes..][..4]
            .try_into()
            .unwrap_or([255; 4]);
        let last = self
            .rgba
            .chunks_exact(row_bytes)
            .rposition(|row| row.chunks_exact(4).any(|p| p != bg))
            .map_or(0, |r| r as u32 + 1);
        self.height = (last + margin).min(self.height).max(1);
        self.rgba.truncate(self.height as usize * row_bytes);
    }
}

#[cfg(test)]
mod tests {
    use super::Image;

    #[test]
    fn crop_keeps_content_and_margin() {
        // 2 × 6 image: content (red) in row 1, background (white) below.
        let mut rgba = vec![255u8; 2 * 6 * 4];
        rgba[8..12].copy_from_slice(&[255, 0, 0, 255]);
        let mut image = Image {
            width: 2,
            height: 6,
            rgba,
        };
        assert_eq!(image.distinct_colours(), 2);
        image.crop_background_rows(1);
        assert_eq!(image.height, 3); // rows 0–1, plus one margin row
        assert_eq!(image.rgba.len(), 2 * 3 * 4);
    }

    #[test]
    fn png_round_trip() {
        let dir = std::env::temp_dir().join(format!("handstack-png-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("t.png");
        let image = Image {
            width: 3,
            height: 2,
            rgba: (0..24).map(|i| (i * 10) as u8).collect(),
        };
        image.write(&path).unwrap();
        assert_eq!(Image::read(&path).unwrap(), image);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
