//! Work shared among the cores, in order: the level pass's bounds ([`super::lod_records`]).

/// `f(0) .. f(n)`, in order, computed in contiguous chunks on up to every core (one thread, the
/// calling one, for fewer than 512 items), `progress` hearing how many are done now and then
/// while the calling thread works on its chunk, and once at the end (on the calling thread).
pub(super) fn on_every_core<T: Send>(
    n: usize,
    f: impl Fn(usize) -> T + Sync,
    progress: &mut dyn FnMut(usize),
) -> Vec<T> {
    use std::sync::atomic::{AtomicUsize, Ordering};
    let cores = std::thread::available_parallelism().map_or(1, |c| c.get());
    let threads = cores.min(n / 256).max(1);
    let chunk = n.div_ceil(threads).max(1);
    let done = AtomicUsize::new(0);
    let (f, done) = (&f, &done);
    let run = move |t: usize| {
        (t * chunk..((t + 1) * chunk).min(n))
            .map(|i| {
                let v = f(i);
                done.fetch_add(1, Ordering::Relaxed);
                v
            })
            .collect::<Vec<T>>()
    };
    let out = std::thread::scope(|s| {
        let others: Vec<_> = (1..threads).map(|t| s.spawn(move || run(t))).collect();
        // The first chunk here, saying how far all are every 256 items.
        let mut first = Vec::with_capacity(chunk);
        for i in 0..chunk.min(n) {
            first.push(f(i));
            if done.fetch_add(1, Ordering::Relaxed) % 256 == 255 {
                progress(done.load(Ordering::Relaxed));
            }
        }
        let rest = others
            .into_iter()
            .flat_map(|p| p.join().expect("a bounds thread panicked"));
        first.into_iter().chain(rest).collect()
    });
    progress(n);
    out
}
