//! Progress bars for long runs: on a terminal only, never with `--json` or
//! when standard error is piped.
use indicatif::{ProgressBar, ProgressStyle};
use std::io::IsTerminal;

/// A bar counting `what`, or `None` when it must not be drawn.
pub fn bar(json: bool, what: &str) -> Option<ProgressBar> {
    if json || !std::io::stderr().is_terminal() {
        return None;
    }
    let bar = ProgressBar::new(0);
    let style = ProgressStyle::with_template(&format!("{{bar:40}} {{pos}}/{{len}} {what} {{elapsed}}"))
        .unwrap_or_else(|_| ProgressStyle::default_bar());
    bar.set_style(style);
    Some(bar)
}
