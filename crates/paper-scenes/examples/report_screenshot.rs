//! `report_screenshot REPORT.html OUT.png [WIDTH]`: a full-page screenshot of a report in
//! headless Chromium (run by `cargo xtask demo --screenshot` for `docs/demo-report.png`).

use paper_scenes::report::browser::Chromium;
use std::path::PathBuf;
use std::process::ExitCode;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let (page, png, width) = match args.as_slice() {
        [page, png] => (page, png, 1400),
        [page, png, w] => match w.parse() {
            Ok(w) => (page, png, w),
            Err(_) => return usage(),
        },
        _ => return usage(),
    };
    let scratch = std::env::temp_dir().join(format!("handstack-shot-{}", std::process::id()));
    let shot = Chromium::find().and_then(|c| {
        c.full_page_screenshot(
            &PathBuf::from(page),
            &PathBuf::from(png),
            width,
            20_000,
            &scratch,
        )
    });
    let _ = std::fs::remove_dir_all(&scratch);
    match shot {
        Ok((w, h)) => {
            println!("screenshot: {png} ({w} × {h} px)");
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("report_screenshot: {e}");
            ExitCode::FAILURE
        }
    }
}

fn usage() -> ExitCode {
    eprintln!("usage: report_screenshot REPORT.html OUT.png [WIDTH]");
    ExitCode::FAILURE
}
