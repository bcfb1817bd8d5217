//! The naive control: direct quadrature of method eq. 3,
//! `u(t_n) = Σ_m ∫_{t_m}^{t_m+1} g(t_n - τ) q(τ) dτ`, O(N²). What a user would
//! otherwise write; used by tests and benchmarks to check the fast form.

/// 8-point Gauss-Legendre nodes on [0, 1] and weights.
const GL8: [(f64, f64); 8] = [
    (0.019_855_071_751_231_856, 0.050_614_268_145_188_13),
    (0.101_666_761_293_186_63, 0.111_190_517_226_687_24),
    (0.237_233_795_041_835_5, 0.156_853_322_938_943_64),
    (0.408_282_678_752_175_1, 0.181_341_891_689_180_99),
    (0.591_717_321_247_824_9, 0.181_341_891_689_180_99),
    (0.762_766_204_958_164_5, 0.156_853_322_938_943_64),
    (0.898_333_238_706_813_4, 0.111_190_517_226_687_24),
    (0.980_144_928_248_768_1, 0.050_614_268_145_188_13),
];

/// `u(t_n)` for `n = 1..=N`: `g(σ)` is the kernel, `force(m, s)` the force in
/// step `m` at local time `s ∈ [0, dt]`. Each step's integral uses
/// 8-point Gauss-Legendre on `sub` sub-intervals.
pub fn direct_convolution(
    g: impl Fn(f64) -> f64,
    force: impl Fn(usize, f64) -> f64,
    dt_s: f64,
    n_steps: usize,
    sub: usize,
) -> Vec<f64> {
    let hs = dt_s / sub as f64;
    (1..=n_steps)
        .map(|n| {
            let t_n = n as f64 * dt_s;
            let mut u = 0.0;
            for m in 0..n {
                for k in 0..sub {
                    for &(x, w) in &GL8 {
                        let s = (k as f64 + x) * hs;
                        u += w * hs * g(t_n - (m as f64 * dt_s + s)) * force(m, s);
                    }
                }
            }
            u
        })
        .collect()
}
