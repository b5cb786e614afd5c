//! A criterion measurement of the CPU time of the whole process (every
//! thread), read from Linux's per-thread scheduler statistics
//! (`/proc/self/task/*/schedstat`, nanoseconds on the CPU).
//!
//! On a shared machine the wall-clock time of a single-threaded benchmark
//! includes the time other processes hold the core; its CPU time does not,
//! so it is the figure to compare with a one-core budget.

use criterion::measurement::{Measurement, ValueFormatter};
use criterion::Throughput;

/// CPU time of all threads of this process, in nanoseconds.
pub fn process_cpu_ns() -> f64 {
    let Ok(tasks) = std::fs::read_dir("/proc/self/task") else {
        return f64::NAN;
    };
    tasks
        .filter_map(|task| {
            let stat = std::fs::read_to_string(task.ok()?.path().join("schedstat")).ok()?;
            stat.split_whitespace().next()?.parse::<f64>().ok()
        })
        .sum()
}

/// Process CPU time as a criterion measurement (values in nanoseconds).
pub struct ProcessCpuTime;

impl Measurement for ProcessCpuTime {
    type Intermediate = f64;
    type Value = f64;

    fn start(&self) -> f64 {
        process_cpu_ns()
    }

    fn end(&self, start: f64) -> f64 {
        process_cpu_ns() - start
    }

    fn add(&self, v1: &f64, v2: &f64) -> f64 {
        v1 + v2
    }

    fn zero(&self) -> f64 {
        0.0
    }

    fn to_f64(&self, value: &f64) -> f64 {
        *value
    }

    fn formatter(&self) -> &dyn ValueFormatter {
        &CpuTimeFormatter
    }
}

/// Formats nanoseconds like criterion's wall-clock durations, marked "cpu".
struct CpuTimeFormatter;

impl ValueFormatter for CpuTimeFormatter {
    fn scale_values(&self, typical_value: f64, values: &mut [f64]) -> &'static str {
        let (factor, unit) = if typical_value < 1e3 {
            (1.0, "ns cpu")
        } else if typical_value < 1e6 {
            (1e-3, "µs cpu")
        } else if typical_value < 1e9 {
            (1e-6, "ms cpu")
        } else {
            (1e-9, "s cpu")
        };
        for v in values {
            *v *= factor;
        }
        unit
    }

    fn scale_throughputs(
        &self,
        _typical_value: f64,
        throughput: &Throughput,
        values: &mut [f64],
    ) -> &'static str {
        let per_iteration = match *throughput {
            Throughput::Bytes(n) | Throughput::BytesDecimal(n) | Throughput::Elements(n) => {
                n as f64
            }
        };
        for v in values {
            *v = per_iteration * 1e9 / *v;
        }
        "elem/cpu s"
    }

    fn scale_for_machines(&self, _values: &mut [f64]) -> &'static str {
        "ns"
    }
}
