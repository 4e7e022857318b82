// SPDX-License-Identifier: Apache-2.0
// svpwm_core: space-vector PWM core -- frequency + modulation index in, six dead-time-protected gates out.
// The top only instantiates and wires its stages (no state of its own), in data-path order:
// configuration (svpwm_config: run, lock, period clamp, the period / dead-time pipeline) -> reference
// registers (svpwm_reference) -> phase accumulator (svpwm_phase_acc: sector + theta') -> the calculator
// (svpwm_calc: a microcoded datapath on one multiplier with the sine ROM (0..60 deg): every input mode,
// hexagon clamp, DPWM, minimum pulse) -> update scheduler and shadow / active registers (svpwm_update)
// -> up/down carrier (svpwm_carrier) -> three comparators (svpwm_compare) -> dead time per leg
// (deadtime) -> six registered gate outputs (svpwm_gate_out); current sampling beside (svpwm_adc).
// Every carrier period follows Minas Table I / AVR495 Table 4-3: symmetric seven segments, V0 split
// at the start and end, V7 in the middle, one leg switching per transition.
// Parameters:
//   Features   - the build: a mask of svpwm_pkg Feat* bits, or a named configuration svpwm_pkg::CfgFull
//                (default: every feature), CfgFoc, CfgVf, CfgMinimal, CfgTiny (model/svpwm_model/config.py,
//                README "Configurations"). A feature not built costs nothing and its inputs are not read:
//                FREQ / VF / POLAR / AB / DQ (mode_i codes 0..4; a code not built gives the zero vector and
//                cfg_err_o; without FREQ and VF no phase accumulator, freq_i not read; without VF vf_*_i,
//                without POLAR and DQ theta_i, without AB and DQ v1_i / v2_i), DPWM (dpwm_i), SIXSTEP (om_i),
//                DTC (dtc_en_i, isign_i), CARRY (vsc_en_i), DTF (dtf_i, dtf_en_i: one dead time, dt_i), UPD
//                (upd_i: valley updates), PRESC (presc_i), SYNC (sync_en_i, sync_i), DSP (the calculator's
//                multiplier: 1 registered 16 x 16, 0 the serial unit), ADC (adc_pt_*_i, win_min_i: two
//                ADC trigger points and the shunt-window report, svpwm_adc; without it adc_trig_o at the
//                valley / peak only and win_*_o 0). TRANSITIONAL: CfgTiny (FREQ only,
//                the compact core before) runs its own serial datapath and ignores mode_i too.
//                SampleLead = svpwm_pkg::sample_lead(Features) (full 250, foc 218, vf 166, minimal 135,
//                tiny 226 clocks)
//   CntWidth   - carrier / period / compare width (8..16)
//   PhaseWidth - in-sector angle fraction bits; f_out = freq * f_clk / (6 * 2^PhaseWidth)
//   FreqWidth  - signed frequency word width (< PhaseWidth)
//   DtWidth    - dead-time width (max 2^DtWidth - 1 clocks)
//   MinPeriod  - smallest half period accepted; smaller period_i is clamped to it (>= SampleLead + 4,
//                the default: svpwm_pkg::min_period(Features), full 254 clocks)
//   FreqMax    - largest |freq_i| accepted; larger is clamped (default: the full signed range)
//   GatePol    - reset value of the gate polarity {low side, high side}, 1 = active-low pins
// Input modes (mode_i, docs/reference.md "Input modes"): FREQ (freq_i + m_i), VF (freq_i, m from the V/f law),
// POLAR (theta_i + m_i), AB (v1_i, v2_i = v_alpha, v_beta), DQ (v1_i, v2_i = v_d, v_q + theta_i); a vector
// beyond the hexagon is clamped to its boundary keeping its angle (sat_o); dpwm_i places the zero vectors
// (SVPWM or bus-clamped DPWM); om_i = 1 replaces the clamp by the six-step law in the angle-driven modes
// (fixed.hex_clamp: the vector moves towards the vertices as m grows past 2/sqrt(3), six-step at m = 2).
// Invalid mode / update codes: zero vector / valley update + cfg_err_o.
// Dead-time compensation (dtc_en_i): each phase's compare value moves by half the dead time against the
// volt-seconds the dead time costs at that phase's current sign (isign_i): C - ceil(dt / 2) for a positive
// current, C + ceil(dt / 2) for a negative one, before the minimum-pulse rule (fixed.dtc_shift).
// Volt-second carry (vsc_en_i): what the minimum-pulse rule drops or widens of a phase is added to its next
// update (fixed.snap_carry), cleared while stopped or tripped and across a period change.
// Timing: new compare values take effect at an update point -- the valley, the peak or both (upd_i;
// presc_i + 1 = carrier opportunities per update) -- and the reference (freq_i, m_i, theta_i, v1_i, v2_i,
// vf_*, dpwm_i, om_i, mode_i, dtc_en_i, isign_i, vsc_en_i) is sampled SampleLead =
// svpwm_pkg::sample_lead(Features) clocks before it (the calculator's program + load 1), in
// the clock before count == SampleLead (down) / P - SampleLead (up). period_i, dt_i, dtf_i, mp_i, upd_i,
// presc_i are sampled there before every valley (period_i as it was one clock earlier) and take effect at it
// (dead times and mp on the gates one clock after it); a changed period, dead time or minimum pulse forces an
// update at that valley. Latency from a reference to the gates: at most a half carrier
// period (double update) or a carrier period (single) + SampleLead + 1 clock to a pole, + 1 + dead
// time to a turned-on gate. freq_i steps the angle from the sample on. The modulator runs one clock
// after en_i (a register: its first valley is the clock after en_i rises, with period_i as it was in the
// clock before en_i rose); after en_i rises the gates stay off until the first update; en_i low turns
// all gates and poles off on the next clock (running_o at once) and aborts a computation.
// Reset: all gates off (at the pins, polarity GatePol). sync_en_i: the carrier starts only with a
// sync_i pulse (another core's sync_o: the clock before its valley, same clock domain), so several cores
// run phase-aligned.
// Safety (README "Safety"): fault_i forces the high sides (and, unless braking, the low sides) off
// combinationally, latched or cycle-by-cycle; a shoot-through interlock is the last stage; the dead
// times, minimum pulse, polarity and safe state are locked by lock_i until reset; out-of-range inputs
// are clamped and flagged, a too short period is lengthened (the dead time is never shortened).
// Dead times: dt_i is the rising-edge one (clocks the high side waits after the low side turned off),
// dtf_i the falling-edge one (clocks the low side waits after the high side turned off) when dtf_en_i is
// 1, else the falling dead time is dt_i; the minimum-pulse threshold is max(dt, dtf) + mp. A build
// without DTF ignores dtf_i / dtf_en_i (one dead time, dt_i, no extra registers).
`default_nettype none

module svpwm_core #(
  parameter logic [31:0] Features = svpwm_pkg::CfgFull,
  parameter int CntWidth   = 16,
  parameter int PhaseWidth = 34,
  parameter int FreqWidth  = 24,
  parameter int DtWidth    = 10,
  parameter int MinPeriod  = svpwm_pkg::min_period(Features),
  parameter int FreqMax    = (1 << (FreqWidth - 1)) - 1,
  parameter logic [1:0] GatePol = 2'b00
) (
  input  logic                        clk_i,           // core clock (default 48 MHz)
  input  logic                        rst_ni,          // asynchronous reset, active low
  input  logic                        en_i,            // run: 1 modulate, 0 all gates off
  input  logic [2:0]                  mode_i,          // 0 FREQ 1 VF 2 POLAR 3 AB 4 DQ (others: error)
  input  logic signed [FreqWidth-1:0] freq_i,          // frequency word, signed (negative = reverse)
  input  logic [15:0]                 m_i,             // magnitude UQ1.15, 0x8000 = 1.0 (FREQ, POLAR)
  input  logic [15:0]                 theta_i,         // electrical angle, 2^16 = 360 deg (POLAR, DQ)
  input  logic signed [15:0]          v1_i,            // v_alpha / v_d, Q2.14, 0x4000 = 1.0 (AB, DQ)
  input  logic signed [15:0]          v2_i,            // v_beta / v_q, Q2.14 (AB, DQ)
  input  logic [15:0]                 vf_boost_i,      // V/f: m at zero frequency, UQ1.15
  input  logic [15:0]                 vf_slope_i,      // V/f: UQ8.8 m-LSBs per 2^(FreqWidth-17) freq LSBs
  input  logic [15:0]                 vf_mmax_i,       // V/f: largest m, UQ1.15
  input  logic [1:0]                  dpwm_i,          // 0 SVPWM 1 DPWMMIN 2 DPWMMAX 3 DPWM1 (60 deg)
  input  logic                        om_i,            // overmodulation: 0 angle-keeping clamp, 1 six-step law
  input  logic [1:0]                  upd_i,           // update at 0 valley 1 peak 2 both (3: error)
  input  logic [7:0]                  presc_i,         // new values every presc_i + 1 opportunities
  input  logic [CntWidth-1:0]         period_i,        // half carrier period in clocks
  input  logic [DtWidth-1:0]          dt_i,            // rising dead time (before a high side), clocks (locked)
  input  logic [DtWidth-1:0]          dtf_i,           // falling dead time (before a low side), clocks (locked)
  input  logic                        dtf_en_i,        // 1: use dtf_i; 0: falling = dt_i (locked)
  input  logic [DtWidth-1:0]          mp_i,            // minimum gate pulse in clocks (locked)
  input  logic                        dtc_en_i,        // dead-time compensation on (sampled with the reference)
  input  logic [2:0]                  isign_i,         // {c, b, a} phase current signs, 1 = negative (into
                                                       // the leg), sampled with the reference
  input  logic                        vsc_en_i,        // volt-second carry of the minimum-pulse rule on
  input  logic [1:0]                  adc_trig_i,      // adc_trig_o at {peak, valley}
  input  logic [1:0]                  adc_pt_en_i,     // ADC trigger point k on (sampled with the reference)
  input  logic [1:0]                  adc_pt_dn_i,     // trigger point k on the down count
  input  logic [2*CntWidth-1:0]       adc_pt_cnt_i,    // {cnt_1, cnt_0} carrier counts of the points
  input  logic [CntWidth:0]           win_min_i,       // minimum low-side shunt window, clocks
  input  logic                        sync_en_i,       // start the carrier only on a sync_i pulse
  input  logic                        sync_i,          // another core's sync_o (same clock domain)
  input  logic                        fault_i,         // trip input, asynchronous, active high
  input  logic                        fault_clear_i,   // clears a latched trip once fault_i is low
  input  logic                        trip_cbc_i,      // trip mode: 0 latched, 1 cycle-by-cycle (locked)
  input  logic                        safe_lo_i,       // safe state: 0 all off, 1 low sides on (locked)
  input  logic [1:0]                  pol_i,           // {lo, hi} pin polarity, 1 = active low (locked;
                                                       // taken only while en_i is low)
  input  logic                        lock_i,          // locks dt, dtf, mp, safe state, trip mode, polarity
  output logic [2:0]                  gate_hi_o,       // {c, b, a} high-side gate pins (polarity applied)
  output logic [2:0]                  gate_lo_o,       // {c, b, a} low-side gate pins (polarity applied)
  output logic [2:0]                  pole_o,          // {c, b, a} modulator states before dead time
  output logic [CntWidth-1:0]         carrier_o,       // carrier value 0..P
  output logic                        carrier_up_o,    // carrier counting up
  output logic                        valley_o,        // pulse: first clock of a carrier period
  output logic                        peak_o,          // pulse: carrier peak
  output logic                        update_o,        // pulse: new compare values active from this clock
  output logic                        adc_trig_o,      // pulse: ADC trigger (valley, peak, points)
  output logic [1:0]                  adc_pt_o,        // pulse: trigger point k (the clock after)
  output logic [3*(CntWidth+1)-1:0]   win_lo_o,        // {c, b, a} low-side windows around the valley
  output logic [3*(CntWidth+1)-1:0]   win_hi_o,        // {c, b, a} high-side windows around the peak
  output logic [2:0]                  win_ok_o,        // {c, b, a} low-side window >= win_min_i
  output logic [1:0]                  win_recon_o,     // phase with the shortest low-side window
  output logic                        sync_o,          // pulse: the clock before a valley (sync_i)
  output logic [2:0]                  sector_o,        // sector (0..5 = seeds' 1..6) of the active values
  output logic [3*CntWidth-1:0]       cmp_o,           // {C_c, C_b, C_a} active now
  output logic [CntWidth-1:0]         period_o,        // active half period
  output logic                        running_o,       // compare values valid, gates modulating
  output logic                        sat_o,           // active values: reference clamped to the hexagon
  output logic                        cfg_err_o,       // invalid mode (active values) or upd_i code
  output logic                        period_clamp_o,  // period_i too short was lengthened at the last sample
  output logic                        freq_clamp_o,    // |freq_i| > FreqMax was clamped at the last sample
  output logic                        fault_o,         // fault_i, synchronised
  output logic                        tripped_o,       // safe state forced (fault_i or latched trip)
  output logic                        locked_o         // configuration locked until reset
);

  // the lowest legal MinPeriod: the sample lead (svpwm_update: clocks from an input sample to the update
  // point) + 4
`ifdef SVPWM_FORMAL_SHORT_LEAD
  // formal/core.sby's cover tasks only (a bounded search does not reach the first update, 250 clocks after
  // a start): svpwm_update's SampleLead is 2 there; the calculator is cut, so no latency to cover. Its
  // proofs run at the shipped lead below.
  localparam int MinPeriodFloor = 4;
`else
  localparam int MinPeriodFloor = svpwm_pkg::min_period_floor(Features);
`endif
  // the features of this build the top reads (svpwm_pkg Feat*; each stage reads its own from Features)
  localparam bit HasAcc   = svpwm_pkg::has_acc(Features);      // the phase accumulator
  localparam bit HasAdc   = svpwm_pkg::has(Features, svpwm_pkg::FeatAdc);
  if ((Features & ~svpwm_pkg::CfgAll) != 0 || (Features & svpwm_pkg::ModeFeatures) == 0)
  begin : gen_bad_features
`ifdef __ICARUS__  // Icarus 11 has no elaboration-time tasks: at time 0
    initial $fatal(1, "svpwm_core: Features 'h%0h: unknown bits or no input mode (%m)", Features);
`else              // at elaboration (Yosys formats $display only, then stops at $error)
    initial $display("svpwm_core: Features 'h%0h: unknown bits or no input mode (%m)", Features);
    $error("svpwm_core: Features 'h%0h: unknown bits or no input mode", Features);
`endif
  end
  if (MinPeriod < MinPeriodFloor || MinPeriod >= (1 << CntWidth)) begin : gen_bad_min_period
`ifdef __ICARUS__  // Icarus 11 has no elaboration-time tasks: at time 0
    initial $fatal(1, "svpwm_core: MinPeriod must be >= %0d (SampleLead + 4), got %0d (%m)",
                   MinPeriodFloor, MinPeriod);
`else              // at elaboration (Yosys formats $display only, then stops at $error)
    initial $display("svpwm_core: MinPeriod must be >= %0d (SampleLead + 4), got %0d (%m)",
                     MinPeriodFloor, MinPeriod);
    $error("svpwm_core: MinPeriod must be >= %0d (SampleLead + 4), got %0d", MinPeriodFloor,
           MinPeriod);
`endif
  end
  if (DtWidth + 2 > CntWidth) begin : gen_bad_dt_width
`ifdef __ICARUS__  // Icarus 11 has no elaboration-time tasks: at time 0
    initial $fatal(1, "svpwm_core: need DtWidth + 2 <= CntWidth (P >= 2 dt), got %0d / %0d (%m)",
                   DtWidth, CntWidth);
`else              // at elaboration (Yosys formats $display only, then stops at $error)
    initial $display("svpwm_core: need DtWidth + 2 <= CntWidth (P >= 2 dt), got %0d / %0d (%m)",
                     DtWidth, CntWidth);
    $error("svpwm_core: need DtWidth + 2 <= CntWidth (P >= 2 dt), got %0d / %0d", DtWidth,
           CntWidth);
`endif
  end
  if (FreqMax < 1 || FreqMax > (1 << (FreqWidth - 1)) - 1) begin : gen_bad_freq_max
`ifdef __ICARUS__  // Icarus 11 has no elaboration-time tasks: at time 0
    initial $fatal(1, "svpwm_core: FreqMax must be 1..2^(FreqWidth-1)-1, got %0d (%m)", FreqMax);
`else              // at elaboration (Yosys formats $display only, then stops at $error)
    initial $display("svpwm_core: FreqMax must be 1..2^(FreqWidth-1)-1, got %0d (%m)", FreqMax);
    $error("svpwm_core: FreqMax must be 1..2^(FreqWidth-1)-1, got %0d", FreqMax);
`endif
  end

  // ---- the nets between the stages ---------------------------------------------------------------
  // configuration (svpwm_config)
  logic                        run, run_next, upd_run, locked, cbc, safe_lo, chg;
  logic [1:0]                  pol;
  logic [CntWidth-1:0]         period_load, period_next;
  logic [DtWidth-1:0]          dt_next, dtf_next, mp_next, dt_act, dtf_act, mp_act;
  logic                        dtf_gt_next, dtf_gt_act, period_clamp;
  // the sampled reference (svpwm_reference)
  logic [2:0]                  ref_mode;
  logic [15:0]                 ref_s0, ref_s1, ref_s2, ref_fabs;
  logic [1:0]                  ref_dpwm;
  logic                        ref_om, ref_dtc, ref_vsc, freq_clamp;
  logic [2:0]                  ref_isign;
  logic signed [FreqWidth-1:0] ref_freq;
  // phase accumulator
  logic [2:0]                  acc_sector;
  logic [PhaseWidth-1:0]       acc_angle;
  // calculator (svpwm_calc) and its operands (svpwm_update)
  logic                        calc_start, calc_busy, calc_done, calc_sat, calc_err, calc_carry_en;
  logic [2:0]                  calc_sector;
  logic [3*CntWidth-1:0]       calc_cmp;
  logic [CntWidth-1:0]         calc_period;
  logic [DtWidth:0]            calc_thr;
  logic [DtWidth-1:0]          calc_hdr, calc_hdf;
  logic [3*DtWidth+5:0]        calc_carry_in, calc_carry_out;
  // update scheduler, shadow / active registers (svpwm_update)
  logic                        upd_sample, upd_smp_valley, upd_take, upd_valid, upd_running;
  logic [3*CntWidth-1:0]       cmp;
  // carrier
  logic [CntWidth-1:0]         count, period_act;
  logic                        up, valley, peak, pre_peak, load, point;
  // comparators, dead time, gate output
  logic [2:0]                  pole, hi_req, lo_req;
  logic                        pole_valid, trip_sync, brake, hold_a;
  // current sampling
  logic [1:0]                  adc_pt;

  // ---- configuration: run, lock, the period clamp, the period / dead-time pipeline ---------------
  svpwm_config #(.Features(Features), .CntWidth(CntWidth), .DtWidth(DtWidth), .MinPeriod(MinPeriod),
                 .GatePol(GatePol)) u_config (
    .clk_i          (clk_i),
    .rst_ni         (rst_ni),
    .en_i           (en_i),
    .sync_en_i      (sync_en_i),
    .sync_i         (sync_i),
    .lock_i         (lock_i),
    .dt_i           (dt_i),
    .dtf_i          (dtf_i),
    .dtf_en_i       (dtf_en_i),
    .mp_i           (mp_i),
    .trip_cbc_i     (trip_cbc_i),
    .safe_lo_i      (safe_lo_i),
    .pol_i          (pol_i),
    .period_i       (period_i),
    .smp_valley_i   (upd_smp_valley),
    .load_i         (load),
    .period_act_i   (period_act),
    .run_o          (run),
    .run_next_o     (run_next),
    .upd_run_o      (upd_run),
    .locked_o       (locked),
    .cbc_o          (cbc),
    .safe_lo_o      (safe_lo),
    .pol_o          (pol),
    .period_load_o  (period_load),
    .period_next_o  (period_next),
    .dt_next_o      (dt_next),
    .dtf_next_o     (dtf_next),
    .dtf_gt_next_o  (dtf_gt_next),
    .mp_next_o      (mp_next),
    .dt_o           (dt_act),
    .dtf_o          (dtf_act),
    .dtf_gt_o       (dtf_gt_act),
    .mp_o           (mp_act),
    .chg_o          (chg),
    .period_clamp_o (period_clamp)
  );

  // ---- reference registers: taken at an update's sample ------------------------------------------
  svpwm_reference #(.Features(Features), .FreqWidth(FreqWidth), .FreqMax(FreqMax)) u_reference (
    .clk_i        (clk_i),
    .rst_ni       (rst_ni),
    .run_i        (run),
    .sample_i     (upd_sample),
    .mode_i       (mode_i),
    .freq_i       (freq_i),
    .m_i          (m_i),
    .theta_i      (theta_i),
    .v1_i         (v1_i),
    .v2_i         (v2_i),
    .vf_boost_i   (vf_boost_i),
    .vf_slope_i   (vf_slope_i),
    .vf_mmax_i    (vf_mmax_i),
    .dpwm_i       (dpwm_i),
    .om_i         (om_i),
    .dtc_en_i     (dtc_en_i),
    .isign_i      (isign_i),
    .vsc_en_i     (vsc_en_i),
    .mode_o       (ref_mode),
    .s0_o         (ref_s0),
    .s1_o         (ref_s1),
    .s2_o         (ref_s2),
    .dpwm_o       (ref_dpwm),
    .om_o         (ref_om),
    .dtc_o        (ref_dtc),
    .isign_o      (ref_isign),
    .vsc_o        (ref_vsc),
    .freq_o       (ref_freq),
    .fabs_o       (ref_fabs),
    .freq_clamp_o (freq_clamp)
  );

  // ---- phase accumulator (FREQ, VF): the split adder (its one chain ends in flip-flops: the chains
  // behind enables were the iCEBreaker's worst paths at 48 MHz), but in the tiny build (the one chain:
  // fewer cells, and the HX1K is fast)
  if (HasAcc) begin : gen_phase
    svpwm_phase_acc #(.PhaseWidth(PhaseWidth), .FreqWidth(FreqWidth),
                      .Split(!svpwm_pkg::is_tiny(Features))) u_phase (
      .clk_i    (clk_i),
      .rst_ni   (rst_ni),
      .run_i    (run),
      .step_i   (ref_freq),         // the sampled frequency word steps the angle from the sample on
      .sector_o (acc_sector),
      .angle_o  (acc_angle)
    );
  end else begin : gen_no_phase     // POLAR / AB / DQ only: the angle comes with the reference
    logic unused_freq;              // (0: freq_i is not read)
    assign unused_freq = ^ref_freq;
    assign acc_sector = '0;
    assign acc_angle  = '0;
  end

  // ---- the calculator: reference -> snapped compare values (the modes and features of the build) ----
  svpwm_calc #(.Features(Features), .CntWidth(CntWidth), .DtWidth(DtWidth)) u_calc (
    .clk_i      (clk_i),
    .rst_ni     (rst_ni),
    .start_i    (calc_start),
    .abort_i    (!run),
    .mode_i     (ref_mode),
    .sector_i   (acc_sector),
    .angle_i    (calc_start ? acc_angle[PhaseWidth-1 -: 16] : 16'd0),   // read only at start_i; held at
                                                                       // 0 otherwise so simulators do
                                                                       // not re-evaluate the calculator
    .theta_i    (ref_s1),
    .m_i        (ref_s0),
    .fabs_i     (ref_fabs),
    .v1_i       (ref_s0),
    .v2_i       (ref_s2),
    .vf_boost_i (ref_s0),
    .vf_slope_i (ref_s1),
    .vf_mmax_i  (ref_s2),
    .dpwm_i     (ref_dpwm),
    .om_i       (ref_om),
    .period_i   (calc_period),
    .thr_i      (calc_thr),
    .isign_i    (ref_isign),
    .hdr_i      (calc_hdr),
    .hdf_i      (calc_hdf),
    .carry_i    (calc_carry_in),
    .carry_en_i (calc_carry_en),
    .busy_o     (calc_busy),
    .done_o     (calc_done),
    .sector_o   (calc_sector),
    .cmp_o      (calc_cmp),
    .sat_o      (calc_sat),
    .err_o      (calc_err),
    .carry_o    (calc_carry_out)
  );

  // ---- update scheduler, the calculator's operands, shadow and active registers --------------------
  svpwm_update #(.Features(Features), .CntWidth(CntWidth), .DtWidth(DtWidth), .MinPeriod(MinPeriod))
  u_update (
    .clk_i           (clk_i),
    .rst_ni          (rst_ni),
    .en_i            (en_i),
    .run_i           (run),
    .upd_run_i       (upd_run),
    .upd_i           (upd_i),
    .presc_i         (presc_i),
    .count_i         (count),
    .up_i            (up),
    .load_i          (load),
    .point_i         (point),
    .period_load_i   (period_load),
    .chg_i           (chg),
    .period_next_i   (period_next),
    .dt_next_i       (dt_next),
    .dtf_next_i      (dtf_next),
    .dtf_gt_next_i   (dtf_gt_next),
    .mp_next_i       (mp_next),
    .period_act_i    (period_act),
    .dt_i            (dt_act),
    .dtf_i           (dtf_act),
    .dtf_gt_i        (dtf_gt_act),
    .mp_i            (mp_act),
    .dtc_i           (ref_dtc),
    .vsc_i           (ref_vsc),
    .trip_i          (trip_sync),
    .calc_done_i     (calc_done),
    .calc_cmp_i      (calc_cmp),
    .calc_sector_i   (calc_sector),
    .calc_sat_i      (calc_sat),
    .calc_err_i      (calc_err),
    .calc_carry_i    (calc_carry_out),
    .sample_o        (upd_sample),
    .smp_valley_o    (upd_smp_valley),
    .calc_start_o    (calc_start),
    .calc_period_o   (calc_period),
    .calc_thr_o      (calc_thr),
    .calc_hdr_o      (calc_hdr),
    .calc_hdf_o      (calc_hdf),
    .calc_carry_o    (calc_carry_in),
    .calc_carry_en_o (calc_carry_en),
    .take_o          (upd_take),
    .cmp_o           (cmp),
    .sector_o        (sector_o),
    .valid_o         (upd_valid),
    .running_o       (upd_running),
    .sat_o           (sat_o),
    .err_o           (cfg_err_o),
    .update_o        (update_o)
  );

  // ---- carrier -----------------------------------------------------------------------------------
  svpwm_carrier #(.CntWidth(CntWidth), .MinPeriod(MinPeriod)) u_carrier (
    .clk_i      (clk_i),
    .rst_ni     (rst_ni),
    .run_i      (run),
    .period_i   (period_load),
    .count_o    (count),
    .up_o       (up),
    .period_o   (period_act),
    .valley_o   (valley),
    .peak_o     (peak),
    .pre_peak_o (pre_peak),
    .load_o     (load),
    .point_o    (point)
  );

  // ---- comparators -------------------------------------------------------------------------------
  svpwm_compare #(.CntWidth(CntWidth)) u_compare (
    .clk_i   (clk_i),
    .rst_ni  (rst_ni),
    .run_i   (upd_running),         // en_i && run && valid: the poles stop with the gates
    .count_i (count),
    .up_i    (up),
    .cmp_i   (cmp),
    .pole_o  (pole),
    .valid_o (pole_valid)
  );

  // ---- dead time per leg; the trip state as the (synchronous) dead-time FSMs see it. The reset hold
  // (no gate on for 2^DtWidth - 1 clocks after a reset) is the same for the three legs: leg a computes
  // it from its counter (hold_a), legs b and c take it (their hold_o is not read)
  assign brake = trip_sync && safe_lo;

  for (genvar ph = 0; ph < 3; ph++) begin : gen_leg
    logic hold_leg;                 // this leg's hold_o (a separate net per leg: no false loop)
    if (ph == 0) begin : gen_hold_a
      assign hold_a = hold_leg;
    end else begin : gen_hold_bc
      logic unused_hold;
      assign unused_hold = hold_leg;
    end
    deadtime #(.DtWidth(DtWidth), .HoldIn(ph != 0)) u_deadtime (
      .clk_i   (clk_i),
      .rst_ni  (rst_ni),
      .en_i    (trip_sync ? safe_lo : (en_i && pole_valid)),   // (pole_valid implies run: formal)
      .brake_i (brake),
      .pole_i  (pole[ph]),
      .dt_i    (dt_act),            // deadtime reads them a clock ahead: new dead times and minimum
      .dtf_i   (dtf_act),           // pulse act on the gates from the clock after the valley
      .mp_i    (mp_act),
      .hold_i  (hold_a),
      .hold_o  (hold_leg),
      .hi_o    (hi_req[ph]),
      .lo_o    (lo_req[ph])
    );
  end

  // ---- last stage: trip forcing, interlock, polarity (combinational after registers) -------------
  svpwm_gate_out u_gate_out (
    .clk_i         (clk_i),
    .rst_ni        (rst_ni),
    .hi_i          (hi_req),
    .lo_i          (lo_req),
    .fault_i       (fault_i),
    .fault_clear_i (fault_clear_i),
    .cbc_i         (cbc),
    .valley_i      (valley),
    .safe_lo_i     (safe_lo),
    .pol_i         (pol),
    .gate_hi_o     (gate_hi_o),
    .gate_lo_o     (gate_lo_o),
    .fault_o       (fault_o),
    .trip_sync_o   (trip_sync),
    .tripped_o     (tripped_o)
  );

  // ---- current sampling (feature ADC): trigger points and the shunt-window report ------------------
  if (HasAdc) begin : gen_adc
    svpwm_adc #(.CntWidth(CntWidth), .DtWidth(DtWidth)) u_adc (
      .clk_i       (clk_i),
      .rst_ni      (rst_ni),
      .run_i       (run),
      .count_i     (count),
      .up_i        (up),
      .valley_i    (valley),
      .peak_i      (peak),
      .period_i    (period_act),
      .sample_i    (upd_sample),
      .take_i      (upd_take),
      .pt_en_i     (adc_pt_en_i),
      .pt_dn_i     (adc_pt_dn_i),
      .pt_cnt_i    (adc_pt_cnt_i),
      .win_min_i   (win_min_i),
      .active_i    (upd_running && !trip_sync),
      .cmp_i       (cmp),
      .dt_i        (dt_act),
      .dtf_i       (dtf_act),
      .mp_i        (mp_act),
      .pt_o        (adc_pt),
      .win_lo_o    (win_lo_o),
      .win_hi_o    (win_hi_o),
      .win_ok_o    (win_ok_o),
      .win_recon_o (win_recon_o)
    );
  end else begin : gen_no_adc       // valley / peak triggers only; the points and window inputs not read
    logic unused_adc;
    assign unused_adc  = ^{adc_pt_en_i, adc_pt_dn_i, adc_pt_cnt_i, win_min_i, upd_take};
    assign adc_pt      = '0;
    assign win_lo_o    = '0;
    assign win_hi_o    = '0;
    assign win_ok_o    = '0;
    assign win_recon_o = '0;
  end

  // the accumulator's low bits set the frequency resolution only; the duty calculator takes the top 16;
  // pre_peak, upd_valid: the update reads point, the formal properties read them
  logic unused_acc;
  assign unused_acc = ^{acc_angle[PhaseWidth-17:0], calc_busy, pre_peak, upd_valid};

  assign pole_o         = pole;
  assign carrier_o      = count;
  assign carrier_up_o   = up;
  assign valley_o       = valley;
  assign peak_o         = peak;
  assign adc_trig_o     = (valley && adc_trig_i[0]) || (peak && adc_trig_i[1]) || adc_pt != 2'b00;
  assign adc_pt_o       = adc_pt;
  assign sync_o         = run_next && load;   // the next clock is a valley (a synced core starts with it)
  assign cmp_o          = cmp;
  assign period_o       = period_act;
  assign running_o      = upd_running;
  assign period_clamp_o = period_clamp;
  assign freq_clamp_o   = freq_clamp;
  assign locked_o       = locked;

`ifdef FORMAL
  // Core-level properties (formal/core.sby proves them with the duty calculator, phase accumulator and
  // minimum-pulse stage cut: their outputs are free, so these hold whatever compare values arrive).
  logic f_past_valid = 1'b0;
  always_ff @(posedge clk_i) f_past_valid <= 1'b1;
  always_comb if (!f_past_valid) assume (!rst_ni);

  logic f_enabled_q;                                  // the core has run since reset
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni)   f_enabled_q <= 1'b0;
    else if (run)  f_enabled_q <= 1'b1;
  end

  logic [2:0] f_hi, f_lo;                             // gate on/off at the pins, polarity undone
  assign f_hi = gate_hi_o ^ {3{pol[0]}};
  assign f_lo = gate_lo_o ^ {3{pol[1]}};

  // a leg never has both gates on, at the pins
  always_comb assert ((f_hi & f_lo) == 3'b000);
  // safe state during reset and until enabled: no high side on (low sides only when braking on a trip)
  always_comb if (!rst_ni) assert (f_hi == 3'b000 && f_lo == 3'b000);
  always_comb if (!f_enabled_q) assert (f_hi == 3'b000 && !upd_valid && !pole_valid);
  always_comb if (!f_enabled_q && !safe_lo) assert (f_lo == 3'b000 || tripped_o == 1'b0);
  // fault asserted => high sides off in the same cycle (and the low sides unless braking)
  always_comb if (fault_i) assert (f_hi == 3'b000);
  always_comb if (fault_i && !safe_lo) assert (f_lo == 3'b000);
  // the carrier stays in [0, P] (P is never below MinPeriod once loaded, never 0); compare values,
  // dead time and minimum pulse change only at a load point
  always_comb if (rst_ni) assert (count <= period_act && period_act != '0);
  always_ff @(posedge clk_i) if (f_past_valid && $past(rst_ni) && rst_ni) begin
    if (cmp != $past(cmp)) assert (($past(load) || $past(pre_peak)) && $past(run));
    if (dt_act != $past(dt_act) || dtf_act != $past(dtf_act) || mp_act != $past(mp_act))
      assert ($past(load));
  end
  // the poles are valid only while the core runs (the legs' enable reads en_i and pole_valid alone)
  always_comb if (rst_ni && pole_valid) assert (run);
  // not vacuous: gates switch, trips happen and release, compare values load
  always_comb cover (rst_ni && f_hi[0] && running_o);
  always_comb cover (rst_ni && f_lo[1] && running_o && dt_act > DtWidth'(2));
  // asymmetric dead times in force and gates switching (builds with DTF; the others have one dead time)
  if (svpwm_pkg::has(Features, svpwm_pkg::FeatDtf)) begin : gen_f_dtf
    always_comb cover (rst_ni && f_hi[2] && running_o && dt_act > DtWidth'(1) && dtf_act > dt_act
                       && locked);
    always_comb cover (rst_ni && f_lo[0] && running_o && dtf_act > DtWidth'(1) && dt_act > dtf_act);
  end
  // ---- issue 27: dead time at the pins across resets and trips. The monitors have no reset
  // (declaration values; they sample rst_ni like any input), so a reset does not make them forget the
  // gate that was on or the dead time in force before it (the core's own dead-time registers are cleared
  // by the reset: F1). f_rel_q: clocks since the release (0 in the release clock), saturating at
  // CntMax + 1; per leg, f_*off_q: clocks the pin has been off before this one, f_*off_dt_q: the other
  // gate's dead time in force in the first clock it was off, f_*off_rst_q: a reset came since it went off.
  // (deadtime reads dt_act / dtf_act a clock ahead: the dead time in force is their value a clock ago.)
  localparam logic [31:0] FW = DtWidth + 1;
  localparam logic [FW-1:0] FSat = {1'b1, {DtWidth{1'b0}}};   // 2^DtWidth = CntMax + 1
  logic [FW-1:0]      f_rel_q = '0;
  logic [DtWidth-1:0] f_dtu_q = '0, f_dtfu_q = '0;
  always_ff @(posedge clk_i) begin
    f_rel_q  <= !rst_ni ? '0 : (f_rel_q >= FSat) ? FSat : f_rel_q + 1'b1;
    f_dtu_q  <= dt_act;
    f_dtfu_q <= dtf_act;
  end
  always_comb assert (f_rel_q <= FSat);
  // (a) no gate on at the pins before clock 2^DtWidth after a release: longer than any dead time the core
  // could have had in force before the reset
  always_comb if (f_hi != 3'b000 || f_lo != 3'b000) assert (f_rel_q == FSat);
  for (genvar ph = 0; ph < 3; ph++) begin : gen_f_leg
    logic [FW-1:0]      f_hoff_q = '0, f_loff_q = '0;
    logic [DtWidth-1:0] f_hoff_dt_q = '0, f_loff_dt_q = '0;
    logic               f_hoff_rst_q = 1'b0, f_loff_rst_q = 1'b0;
    always_ff @(posedge clk_i) begin
      f_hoff_q     <= f_hi[ph] ? '0 : (f_hoff_q >= FSat) ? FSat : f_hoff_q + 1'b1;
      f_loff_q     <= f_lo[ph] ? '0 : (f_loff_q >= FSat) ? FSat : f_loff_q + 1'b1;
      if (f_hi[ph]) f_hoff_dt_q <= dtf_act;
      if (f_lo[ph]) f_loff_dt_q <= dt_act;
      f_hoff_rst_q <= f_hi[ph] ? 1'b0 : (f_hoff_rst_q || !rst_ni);
      f_loff_rst_q <= f_lo[ph] ? 1'b0 : (f_loff_rst_q || !rst_ni);
    end
    always_comb assert (f_hoff_q <= FSat && f_loff_q <= FSat);
    // (a) at the pins a high side turned on by its dead-time register only after its low side has been
    // off for the rising dead time in force (or swaps at 0), a low side after the falling one; every pin
    // turn-on after a reset since the other gate went off: more than the dead time in force when it went
    // off, and more than 2^DtWidth - 1 clocks. (A pin turned on by the end of a trip's forcing, its
    // register already on, is not in the first clause: with the falling dead time raised at a valley in
    // the meantime and safe_lo_i set during the trip, PDR finds the low-side gap shorter than the new dtf,
    // frame 1026; see the issue-27 report.)
    always_ff @(posedge clk_i) if (f_past_valid && f_hi[ph] && !$past(f_hi[ph])) begin
      if (!$past(hi_req[ph])) assert ($past(f_dtu_q) == '0 || f_loff_q >= FW'($past(f_dtu_q)));
      if (f_loff_rst_q) assert (f_loff_q > FW'(f_loff_dt_q) && f_loff_q == FSat);
    end
    always_ff @(posedge clk_i) if (f_past_valid && f_lo[ph] && !$past(f_lo[ph])) begin
      if (!$past(lo_req[ph])) assert ($past(f_dtfu_q) == '0 || f_hoff_q >= FW'($past(f_dtfu_q)));
      if (f_hoff_rst_q) assert (f_hoff_q > FW'(f_hoff_dt_q) && f_hoff_q == FSat);
    end
  end
  // (d) F1 at the pins: a reset after a high side was on (f_hi_ever_q), then braking, and the low side
  // on after the hold
  logic f_hi_ever_q = 1'b0;
  always_ff @(posedge clk_i) if (f_hi[0]) f_hi_ever_q <= 1'b1;
  // (builds with peak updates: with valley updates only (minimal, tiny) the first gate, a high side that
  // the reset then cuts, and the hold come too late for the cover depth, 30)
  if (svpwm_pkg::has(Features, svpwm_pkg::FeatUpd)) begin : gen_f_f1_cover
    always_ff @(posedge clk_i) if (f_past_valid)
      cover (rst_ni && f_lo[0] && !$past(f_lo[0]) && safe_lo && gen_f_leg[0].f_hoff_rst_q && f_hi_ever_q);
  end
  always_ff @(posedge clk_i) cover (f_past_valid && $past(tripped_o) && !tripped_o && running_o);
  always_ff @(posedge clk_i) cover (f_past_valid && rst_ni && cmp != $past(cmp) && locked);
`endif

endmodule

`default_nettype wire
