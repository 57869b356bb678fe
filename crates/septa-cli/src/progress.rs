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

/// A spinner naming a stage without a count (writing, region surfaces,
/// label surfaces) with its elapsed seconds, redrawn each second; drawn on
/// a terminal only (`None` when standard error is piped, with `--json` or `-q`).
pub fn stage(quiet: bool, what: &str) -> Option<ProgressBar> {
    if quiet || !std::io::stderr().is_terminal() {
        return None;
    }
    let bar = ProgressBar::new_spinner();
    bar.set_style(
        ProgressStyle::with_template("{spinner} {msg} {elapsed}").unwrap_or_else(|_| ProgressStyle::default_spinner()),
    );
    bar.set_message(what.to_string());
    bar.enable_steady_tick(std::time::Duration::from_millis(1000));
    Some(bar)
}

/// Runs `work` under a [`stage`] spinner and clears it afterwards.
pub fn during<T>(quiet: bool, what: &str, work: impl FnOnce() -> T) -> T {
    let bar = stage(quiet, what);
    let out = work();
    if let Some(bar) = bar {
        bar.finish_and_clear();
    }
    out
}

/// Moves a block bar on as blocks finish; when the last block is done the
/// bar becomes a spinner naming the stage after the blocks (`next`: the
/// topology of patches, chains and cells, which has no block count), so a
/// long topology stage does not look like a hang at 100%.
pub fn blocks_then(bar: &ProgressBar, done: usize, total: usize, next: &str) {
    bar.set_length(total as u64);
    bar.set_position(done as u64);
    if done == total && bar.message().is_empty() {
        bar.set_style(
            ProgressStyle::with_template("{spinner} {msg} {elapsed}")
                .unwrap_or_else(|_| ProgressStyle::default_spinner()),
        );
        bar.set_message(next.to_string());
        bar.enable_steady_tick(std::time::Duration::from_millis(1000));
    }
}

/// A counted bar over a network's blocks and the library progress callback
/// that moves it; after the last block it names the stage `next` (see
/// [`blocks_then`]). Both `None` when no bar may be drawn.
pub fn block_bar(quiet: bool, next: &str) -> (Option<ProgressBar>, Option<septa::Progress>) {
    let Some(bar) = self::bar(quiet, "blocks") else {
        return (None, None);
    };
    let (b, next) = (bar.clone(), next.to_string());
    let progress = septa::Progress(std::sync::Arc::new(move |done, total| blocks_then(&b, done, total, &next)));
    (Some(bar), Some(progress))
}
