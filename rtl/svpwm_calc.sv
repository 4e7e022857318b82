// SPDX-License-Identifier: Apache-2.0
// svpwm_calc: the core's one calculator -- a reference in any input mode -> sector, dwell times, hexagon
// clamp, compare values (AVR495 Table 4-3), zero-vector placement and the minimum-pulse rule; exactly
// model/svpwm_model/fixed.py: snap_min_pulse(modulate(...)).
// (TRANSITIONAL: this wraps the old svpwm_duty + svpwm_minpulse / svpwm_duty_lite behind the final ports.)
// Parameters: Compact - 1: FREQ mode, continuous SVPWM only (mode_i, theta_i, v1_i, v2_i, vf_*, dpwm_i
//             ignored); CntWidth - period / compare width (8..16); DtWidth - thr_i is DtWidth + 1 bits.
// Latency: svpwm_pkg::calc_latency(Compact) clocks from start_i to done_o. Restrictions: sector_i and
// angle_i are read at start_i only; every other input must hold from start_i until done_o (the core's
// sampled registers do); start_i is ignored while busy_o; period_i >= 2 thr_i.
`default_nettype none

module svpwm_calc #(
  parameter bit Compact  = 1'b0,
  parameter int CntWidth = 16,
  parameter int DtWidth  = 10
) (
  input  logic                  clk_i,        // core clock
  input  logic                  rst_ni,       // asynchronous reset, active low
  input  logic                  start_i,      // start a computation (ignored while busy_o)
  input  logic                  abort_i,      // back to idle, no done_o, the results hold
  input  logic [2:0]            mode_i,       // input mode (svpwm_core)
  input  logic [2:0]            sector_i,     // phase accumulator: sector 0..5 (FREQ, VF), at start_i
  input  logic [15:0]           angle_i,      // phase accumulator: theta' / 60 deg, UQ0.16, at start_i
  input  logic [15:0]           theta_i,      // electrical angle, 2^16 = 360 deg (POLAR, DQ)
  input  logic [15:0]           m_i,          // magnitude, UQ1.15 (FREQ, POLAR)
  input  logic [15:0]           fabs_i,       // |frequency word| >> (FreqWidth - 17) (VF)
  input  logic signed [15:0]    v1_i,         // v_alpha or v_d, Q2.14 (AB, DQ)
  input  logic signed [15:0]    v2_i,         // v_beta or v_q, Q2.14 (AB, DQ)
  input  logic [15:0]           vf_boost_i,   // V/f: m at zero frequency, UQ1.15
  input  logic [15:0]           vf_slope_i,   // V/f: m LSBs per fabs_i LSB, UQ8.8
  input  logic [15:0]           vf_mmax_i,    // V/f: largest m, UQ1.15
  input  logic [1:0]            dpwm_i,       // 0 SVPWM, 1 DPWMMIN, 2 DPWMMAX, 3 DPWM1 (60 deg)
  input  logic [CntWidth-1:0]   period_i,     // half carrier period P the compare values are scaled to
  input  logic [DtWidth:0]      thr_i,        // dead time + minimum pulse (minimum-pulse rule)
  output logic                  busy_o,       // a computation is running
  output logic                  done_o,       // one-cycle pulse: the outputs below are new
  output logic [2:0]            sector_o,     // sector of the result
  output logic [3*CntWidth-1:0] cmp_o,        // {C_c, C_b, C_a}, each in [0, P], snapped
  output logic                  sat_o,        // the reference was clamped to the hexagon
  output logic                  err_o         // invalid mode: zero vector
);

  if (Compact) begin : gen_lite
    svpwm_duty_lite #(.CntWidth(CntWidth), .DtWidth(DtWidth)) u_duty (
      .clk_i    (clk_i),
      .rst_ni   (rst_ni),
      .start_i  (start_i),
      .abort_i  (abort_i),
      .sector_i (sector_i),
      .angle_i  (angle_i),
      .m_i      (m_i),
      .period_i (period_i),
      .thr_i    (thr_i),
      .busy_o   (busy_o),
      .done_o   (done_o),
      .sector_o (sector_o),
      .cmp_o    (cmp_o),
      .sat_o    (sat_o)
    );
    assign err_o = 1'b0;

    logic unused_full;
    assign unused_full = ^{mode_i, theta_i, v1_i, v2_i, vf_boost_i, vf_slope_i, vf_mmax_i, dpwm_i, fabs_i};
  end else begin : gen_full
    logic [3*CntWidth-1:0] duty_cmp;
    logic                  duty_done, duty_busy, snap_busy_q;

    svpwm_duty #(.CntWidth(CntWidth)) u_duty (
      .clk_i      (clk_i),
      .rst_ni     (rst_ni),
      .start_i    (start_i && !abort_i),
      .abort_i    (abort_i),
      .mode_i     (mode_i),
      .sector_i   (sector_i),
      .angle_i    (angle_i),
      .theta_i    (theta_i),
      .m_i        (m_i),
      .fabs_i     (fabs_i),
      .v1_i       (v1_i),
      .v2_i       (v2_i),
      .vf_boost_i (vf_boost_i),
      .vf_slope_i (vf_slope_i),
      .vf_mmax_i  (vf_mmax_i),
      .dpwm_i     (dpwm_i),
      .period_i   (period_i),
      .busy_o     (duty_busy),
      .done_o     (duty_done),
      .sector_o   (sector_o),
      .cmp_o      (duty_cmp),
      .sat_o      (sat_o),
      .err_o      (err_o)
    );

    svpwm_minpulse #(.CntWidth(CntWidth), .DtWidth(DtWidth)) u_minpulse (
      .clk_i    (clk_i),
      .rst_ni   (rst_ni),
      .start_i  (duty_done),
      .cmp_i    (duty_cmp),
      .period_i (period_i),
      .thr_i    (thr_i),
      .done_o   (done_o),
      .cmp_o    (cmp_o)
    );

    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni)        snap_busy_q <= 1'b0;
      else if (abort_i)   snap_busy_q <= 1'b0;
      else if (duty_done) snap_busy_q <= 1'b1;
      else if (done_o)    snap_busy_q <= 1'b0;
    end
    assign busy_o = duty_busy || snap_busy_q;
  end

endmodule

`default_nettype wire
