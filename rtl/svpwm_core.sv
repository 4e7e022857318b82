// SPDX-License-Identifier: Apache-2.0
// svpwm_core: space-vector PWM core -- frequency + modulation index in, six dead-time-protected gates out.
// Pipeline: phase accumulator (sector + theta') -> the calculator (svpwm_calc: a microcoded datapath on
// one multiplier with the sine ROM (0..60 deg): every input mode, hexagon clamp, DPWM, minimum pulse)
// -> up/down carrier -> three comparators -> dead time per leg -> six registered gate outputs.
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

  // clocks from an input sample (inputs taken in the clock before) to the update point
`ifdef SVPWM_FORMAL_SHORT_LEAD
  // formal/core.sby's cover tasks only (a bounded search does not reach the first update, 250 clocks after
  // a start); the calculator is cut there, so no latency to cover. Its proofs run at the shipped lead below.
  localparam int SampleLead     = 2;
  localparam int MinPeriodFloor = 4;
`else
  localparam int SampleLead     = svpwm_pkg::sample_lead(Features);       // calculator + load 1
  localparam int MinPeriodFloor = svpwm_pkg::min_period_floor(Features);
`endif
  // the features of this build (svpwm_pkg Feat*; the calculator reads its own from Features)
  localparam bit HasAcc   = svpwm_pkg::has_acc(Features);      // the phase accumulator
  localparam bit HasVf    = svpwm_pkg::has(Features, svpwm_pkg::FeatVf);
  localparam bit HasXy    = svpwm_pkg::has_xy(Features);
  localparam bit HasDpwm  = svpwm_pkg::has(Features, svpwm_pkg::FeatDpwm);
  localparam bit HasSix   = svpwm_pkg::has(Features, svpwm_pkg::FeatSixstep);
  localparam bit HasDtc   = svpwm_pkg::has(Features, svpwm_pkg::FeatDtc);
  localparam bit HasCarry = svpwm_pkg::has(Features, svpwm_pkg::FeatCarry);
  localparam bit HasDtf   = svpwm_pkg::has(Features, svpwm_pkg::FeatDtf);
  localparam bit HasUpd   = svpwm_pkg::has(Features, svpwm_pkg::FeatUpd);
  localparam bit HasPresc = svpwm_pkg::has(Features, svpwm_pkg::FeatPresc);
  localparam bit HasSync  = svpwm_pkg::has(Features, svpwm_pkg::FeatSync);
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

  // ---- run_q: a register, en_i of the clock before (the modulator starts one clock after en_i rises:
  // fixed.START_DELAY; en_i low still turns the gates off on the next clock: the legs and poles read
  // en_i), but not in the first ArmClocks (4) clocks after reset, so that the configuration registers,
  // the lowest legal period, the clamped period and then the idle loads (period clamped for the dead
  // time, frequency) all happen before the carrier starts; with sync_en_i, not before a sync_i pulse
  // (another core's sync_o: the clock before its valley). Every enable of the core reads run_q (or its
  // twin upd_run) from a flip-flop.
  logic [svpwm_pkg::ArmClocks-2:0] armed_q;
  logic       run_d, run_q;
  // upd_run: for the update logic below (take, pending, valid, the active dead time: ~120 enables) a
  // second run register, equal to run_q in every clock (formal), with its own feedback so that synthesis
  // keeps it: one run net for all enables was the iCEBreaker's worst path at 48 MHz (run -> pending_q,
  // 23 ns). Not in the tiny build (the HX1K is full and fast enough): there upd_run is run_q.
  logic       upd_run;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      armed_q <= '0;
      run_q   <= 1'b0;
    end else begin
      armed_q <= {armed_q[svpwm_pkg::ArmClocks-3:0], 1'b1};
      run_q   <= run_d;
    end
  end

  // a build without the sync start, the update modes or the prescaler ignores those inputs
  logic       sync_en;
  logic [1:0] upd_in;
  logic [7:0] presc_in;

  assign sync_en  = HasSync ? sync_en_i : 1'b0;
  assign upd_in   = HasUpd ? upd_i : 2'd0;
  assign presc_in = HasPresc ? presc_i : 8'd0;

  assign run_d = en_i && armed_q[svpwm_pkg::ArmClocks-2] && (run_q || !sync_en || sync_i);

  if (!svpwm_pkg::is_tiny(Features)) begin : gen_upd_run
    logic upd_run_d, upd_run_q;

    assign upd_run_d = en_i && armed_q[svpwm_pkg::ArmClocks-2] && (upd_run_q || !sync_en || sync_i);

    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) upd_run_q <= 1'b0;
      else         upd_run_q <= upd_run_d;
    end

    assign upd_run = upd_run_q;
  end else begin : gen_one_run
    assign upd_run = run_q;
  end

  // ---- configuration registers, locked by lock_i until reset ----------------------------------
  logic               locked_q;
  logic [DtWidth-1:0] dt_cfg_q, dtf_cfg_q, mp_cfg_q;   // dtf_cfg_q: the falling dead time, dtf_en_i resolved
  logic [DtWidth-1:0] dtx_cfg_q;                       // max(dt, dtf): registered beside them (timing)
  logic               cbc_q, safe_lo_q;
  logic [1:0]         pol_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      locked_q  <= 1'b0;
      dt_cfg_q  <= '0;
      dtf_cfg_q <= '0;
      dtx_cfg_q <= '0;
      dfg_cfg_q <= 1'b0;
      mp_cfg_q  <= '0;
      cbc_q     <= 1'b0;
      safe_lo_q <= 1'b0;
      pol_q     <= GatePol;
    end else begin
      if (lock_i) locked_q <= 1'b1;
      if (!locked_q) begin
        dt_cfg_q  <= dt_i;
        // (a build without DTF: dtf = dt from here on, in every stage; synthesis merges the copies)
        dtf_cfg_q <= (HasDtf && dtf_en_i) ? dtf_i : dt_i;
        dtx_cfg_q <= (HasDtf && dtf_en_i && dtf_i > dt_i) ? dtf_i : dt_i;
        dfg_cfg_q <= HasDtf && dtf_en_i && dtf_i > dt_i;
        mp_cfg_q  <= mp_i;
        cbc_q     <= trip_cbc_i;
        safe_lo_q <= safe_lo_i;
        if (!run_q) pol_q <= pol_i;
      end
    end
  end

  // ---- the falling dead time travels beside dt through every stage (configuration, use, next, active),
  // so both change together at a valley, and so does "dtf > dt" (dfg_*), which selects the larger one
  // for the calculator's minimum-pulse threshold thr = max(dt, dtf) + mp: a 10-bit compare in front of
  // that adder would not meet 48 MHz on the UP5K, and a registered max or thr at every stage adds 30
  // flip-flops to the enables the run_q register drives (the board's slowest path). A build without DTF
  // has one dead time: its dtf is dt at every stage (its dtf_* / dfg_* flops are never read and not
  // built) and, without UPD too, its calculator reads dt_next_q + mp_next_q.
  logic [DtWidth-1:0] dtf_cfg, dtx_cfg, dtf_act;
  logic [DtWidth-1:0] dtf_use_q, dtf_next_d, dtf_next_q, dtf_d, dtf_q;
  logic [DtWidth-1:0] dt_use_q, dt_next_q, dt_q;
  logic               dfg_cfg_q, dfg_use_q, dfg_next_d, dfg_next_q, dfg_d, dfg_q;   // dtf > dt
  logic [DtWidth-1:0] calc_dtx;
  logic [DtWidth-1:0] calc_mp;

  assign dtf_cfg  = HasDtf ? dtf_cfg_q : dt_q;        // one dead time: = dtf_act, so no compare (dtf_ne 0)
  assign dtx_cfg  = HasDtf ? dtx_cfg_q : dt_cfg_q;
  assign dtf_act  = HasDtf ? dtf_q     : dt_q;

  // ---- input clamps (bad input gets the nearest legal value and a flag) --------------------------
  logic [CntWidth-1:0]         period_clamped, period_low;
  logic [DtWidth:0]            thr;             // max(dt, dtf) + minimum pulse
  logic signed [FreqWidth-1:0] freq_clamped;
  logic                        period_under, freq_over;

  assign thr            = {1'b0, dtx_cfg} + {1'b0, mp_cfg_q};
  assign period_low     = (CntWidth'({thr, 1'b0}) > CntWidth'(MinPeriod)) ? CntWidth'({thr, 1'b0})
                                                                        : CntWidth'(MinPeriod);

  // the lowest legal period is registered (off the sampling paths); dt / mp are used one clock later
  // too (dt_use_q / mp_use_q), so a period is always clamped for the dead time it is used with
  logic [CntWidth-1:0] period_low_q;
  logic [DtWidth-1:0]  mp_use_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      period_low_q <= CntWidth'(MinPeriod);
      dt_use_q     <= '0;
      dtf_use_q    <= '0;
      dfg_use_q    <= 1'b0;
      mp_use_q     <= '0;
    end else begin
      period_low_q <= period_low;
      dt_use_q     <= dt_cfg_q;
      dtf_use_q    <= dtf_cfg_q;
      dfg_use_q    <= dfg_cfg_q;
      mp_use_q     <= mp_cfg_q;
    end
  end

  assign period_under   = period_i < period_low_q;

  assign period_clamped = period_under ? period_low_q : period_i;

  // -(W'(x)), not -W'(x): Yosys 0.70 drops a unary operator in front of a size cast (the simulators do not;
  // tb/cocotb/svpwm_core/test_svpwm_core_yosys.py checks the clamp on Yosys' netlist)
  // (a build without FREQ and VF has no phase accumulator: freq_i is not read)
  assign freq_over      = HasAcc && (freq_i > FreqWidth'(FreqMax) || freq_i < -(FreqWidth'(FreqMax)));
  assign freq_clamped   = !HasAcc ? '0 : !freq_over ? freq_i : freq_i[FreqWidth-1] ? -(FreqWidth'(FreqMax))
                                                                                  : FreqWidth'(FreqMax);

  // ---- carrier -----------------------------------------------------------------------------------
  logic [CntWidth-1:0] count, period_act, period_load;
  logic                up, valley, peak, pre_peak, load;
  logic                upd_point;   // running, the next clock is a valley or a peak (load || pre_peak)

  logic [CntWidth-1:0] period_next_d, period_next_q;
  logic [DtWidth-1:0]  dt_next_d, dt_d, mp_next_d, mp_next_q, mp_d, mp_q;

  // the clamped period is registered too (one clock after the port), and so is the comparison that forces
  // an update (valid in every clock but the one after a load, i.e. at every sample point): the sample
  // strobes then reach the ~150 register enables they drive straight from flip-flops
  logic [CntWidth-1:0] period_clamped_q;
  logic                period_under_q, ne_pin_q, ne_low_q, dtmp_chg_q, chg;
  // one compare per field, kept, then their OR: 4 LUT levels for the 60 bits (ABC made 7 of the flat
  // expression on the UP5K, the core's slowest path after the calculator's)
  (* keep *) logic     dt_ne, dtf_ne, mp_ne;

  assign dt_ne  = dt_cfg_q != dt_q;
  assign dtf_ne = dtf_cfg != dtf_act;
  assign mp_ne  = mp_cfg_q != mp_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      period_clamped_q <= CntWidth'(MinPeriod);
      period_under_q   <= 1'b0;
      ne_pin_q         <= 1'b0;
      ne_low_q         <= 1'b0;
      dtmp_chg_q       <= 1'b0;
    end else begin
      period_clamped_q <= period_clamped;
      period_under_q   <= period_under;
      ne_pin_q         <= period_i != period_act;
      ne_low_q         <= period_low_q != period_act;
      dtmp_chg_q       <= dt_ne || dtf_ne || mp_ne;
    end
  end

  // == (period_clamped_q != period_act || dt_use_q != dt_q || dtf_use_q != dtf_act || mp_use_q != mp_q): the
  // compares are registered side by side (the period one for both sides of the clamp), the clamp's choice
  // after them
  assign chg = (period_under_q ? ne_low_q : ne_pin_q) || dtmp_chg_q;

  logic signed [FreqWidth-1:0] freq_d, freq_q;
  logic                period_clamp_d, period_clamp_q, freq_clamp_d, freq_clamp_q;

  // idle: the clamped port, registered (the carrier's period and period - 1 then start from flip-flops,
  // not from en_i, the period compare and its mux); the core idles >= 4 clocks after reset (armed_q)
  assign period_load = run_q ? period_next_q : period_clamped_q;

  svpwm_carrier #(.CntWidth(CntWidth), .MinPeriod(MinPeriod)) u_carrier (
    .clk_i      (clk_i),
    .rst_ni     (rst_ni),
    .run_i      (run_q),
    .period_i   (period_load),
    .count_o    (count),
    .up_o       (up),
    .period_o   (period_act),
    .valley_o   (valley),
    .peak_o     (peak),
    .pre_peak_o (pre_peak),
    .load_o     (load),
    .point_o    (upd_point)
  );

  // ---- sample points: SampleLead clocks before each valley (count == SampleLead counting down) and
  // each peak (count == P - SampleLead counting up); the inputs are taken in the clock before (vps, pps),
  // from registered compares one clock earlier still (count == SampleLead + 2 / P - SampleLead - 2) ----
  logic [CntWidth-1:0] pl2_d, pl2_q;           // P - SampleLead - 2 of the active period
  logic                vps_d, vps_q, pps_d, pps_q, vps, pps;

  assign pl2_d = load ? period_load - CntWidth'(SampleLead + 2) : pl2_q;
  assign vps_d = run_q && !up && count == CntWidth'(SampleLead + 2);
  assign pps_d = run_q && up && count == pl2_q;
  assign vps   = run_q && vps_q;
  assign pps   = run_q && pps_q;

  // ---- update control: which opportunities update (upd, prescaler), forced updates --------------
  localparam logic [1:0] UpdPeak = 2'd1, UpdBoth = 2'd2;   // 2'd0: valley

  logic       updv_d, updv_q, updp_d, updp_q;   // the update mode as "valley / peak opportunities used"
  logic       cz_d, cz_q;                       // cnt_d == 0, registered (the prescaler lets this one update)
  logic       upd_err_d, upd_err_q;
  logic [7:0] presc_d, presc_q, cnt_d, cnt_q;
  logic       opp_v, opp_p, forced, event_now;

  assign opp_v     = vps && updv_q;
  assign opp_p     = pps && updp_q;
  assign forced    = vps && chg;
  assign event_now = ((opp_v || opp_p) && cz_q) || forced;

  always_comb begin
    updv_d    = updv_q;
    updp_d    = updp_q;
    upd_err_d = upd_err_q;
    presc_d   = presc_q;
    cnt_d     = cnt_q;
    cz_d      = cz_q;
    if (opp_v || opp_p) begin
      cnt_d = (cnt_q >= presc_q) ? '0 : cnt_q + 8'd1;
      cz_d  = cnt_q >= presc_q;
    end
    if (!run_q || vps) begin               // update mode and prescaler: before each valley (or idle)
      updv_d    = upd_in != UpdPeak;       // an invalid code (3) is a valley update (+ upd_err)
      updp_d    = upd_in == UpdPeak || upd_in == UpdBoth;
      upd_err_d = upd_in == 2'd3;
      presc_d   = presc_in;
    end
    if (!run_q) begin
      cnt_d = '0;
      cz_d  = 1'b1;
    end
  end

  // ---- reference registers: taken at an update's sample. Three 16-bit slots hold the inputs the mode
  // reads (fixed.input_slots): s0 = m (FREQ, POLAR, invalid) / vf_boost (VF) / v1 (AB, DQ), s1 = theta /
  // vf_slope (VF), s2 = v2 / vf_mmax (VF); the calculator's ports of one slot share it (a mode never reads
  // two inputs of one slot, and fixed.modulate reads no input its mode does not use) -----------------
  logic [2:0]  mode_q;
  logic [15:0] s0_d, s0_q, s1_d, s1_q, s2_d, s2_q;
  logic [1:0]  dpwm_q;
  logic        dtc_q, om_q, vsc_q;
  logic [2:0]  isign_q;
  logic        in_vf, in_xy;

  assign in_vf = HasVf && mode_i == 3'(svpwm_pkg::ModeVf);
  assign in_xy = HasXy && (mode_i == 3'(svpwm_pkg::ModeAb) || mode_i == 3'(svpwm_pkg::ModeDq));
  assign s0_d  = in_vf ? vf_boost_i : in_xy ? v1_i : m_i;
  assign s1_d  = in_vf ? vf_slope_i : theta_i;
  assign s2_d  = in_vf ? vf_mmax_i : v2_i;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      mode_q <= '0;
      s0_q   <= '0;
      s1_q   <= '0;
      s2_q   <= '0;
      dpwm_q <= '0;
      dtc_q   <= 1'b0;
      isign_q <= '0;
      om_q    <= 1'b0;
      vsc_q   <= 1'b0;
    end else if (event_now) begin
      mode_q <= mode_i;
      s0_q   <= s0_d;
      s1_q   <= s1_d;
      s2_q   <= s2_d;
      dpwm_q <= HasDpwm ? dpwm_i : 2'd0;
      dtc_q   <= HasDtc && dtc_en_i;
      isign_q <= HasDtc ? isign_i : 3'd0;
      om_q    <= HasSix && om_i;
      vsc_q   <= HasCarry && vsc_en_i;
    end
  end

  // ---- phase accumulator -------------------------------------------------------------------------
  logic [2:0]            acc_sector;
  logic [PhaseWidth-1:0] acc_angle;

  // the split adder (its one chain ends in flip-flops: the chains behind enables were the iCEBreaker's
  // worst paths at 48 MHz), but in the tiny build (the one chain: fewer cells, and the HX1K is fast)
  if (HasAcc) begin : gen_phase
    svpwm_phase_acc #(.PhaseWidth(PhaseWidth), .FreqWidth(FreqWidth),
                      .Split(!svpwm_pkg::is_tiny(Features))) u_phase (
      .clk_i    (clk_i),
      .rst_ni   (rst_ni),
      .run_i    (run_q),
      .step_i   (freq_q),           // the sampled frequency word steps the angle from the sample on
      .sector_o (acc_sector),
      .angle_o  (acc_angle)
    );
  end else begin : gen_no_phase     // POLAR / AB / DQ only: the angle comes with the reference
    assign acc_sector = '0;
    assign acc_angle  = '0;
  end

  // |frequency word| >> (FreqWidth - 17) for the V/f law (freq_q is clamped: no overflow), registered:
  // one clock after freq_q, i.e. from the calculator's first step on (its programs read it in step 1 at
  // the earliest, as the operand of step 2: model/tests/test_calc_prog.py checks it)
  logic [FreqWidth-1:0] fmag;
  logic [15:0]          fabs_d, fabs_q;

  assign fmag = freq_q[FreqWidth-1] ? FreqWidth'(-freq_q) : FreqWidth'(freq_q);
  if (FreqWidth >= 17) begin : gen_fabs_shr
    assign fabs_d = fmag[FreqWidth-2 -: 16];
  end else begin : gen_fabs_shl
    assign fabs_d = 16'({fmag[FreqWidth-2:0], (17 - FreqWidth)'(0)});
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) fabs_q <= '0;
    else         fabs_q <= fabs_d;
  end

  // ---- duty calculator: started in the clock after the sample (event_q) --------------------------
  logic                  start_q, ev_valley_q, pending_d, pending_q;
  logic [2:0]            duty_sector;
  logic                  duty_busy, duty_sat, duty_err;
  logic [CntWidth-1:0]   calc_period_d, calc_period_q;
  logic [DtWidth:0]      calc_thr_d, calc_thr_q;
  logic [DtWidth-1:0]    calc_hdr_d, calc_hdr_q, calc_hdf_d, calc_hdf_q, hd_dt, hd_dtf;
  // volt-second carry (fixed.snap_carry): per phase what the minimum-pulse rule dropped or widened at the
  // last update (car_q, for the period car_per_q), given to the next computation for the same period; cleared
  // while stopped or tripped, and not given across a period change
  localparam int EW = DtWidth + 2;
  logic [3*EW-1:0]       car_d, car_q, snap_car;
  logic                  trip_sync, brake;     // (the trip state: svpwm_gate_out, below)
  logic [CntWidth-1:0]   car_per_d, car_per_q;
  logic                  car_ok_d, car_ok_q;
  logic [1:0]            take_q;               // take, one and two clocks before

  // dead-time compensation amounts for the calculator (fixed.dtc_amounts): ceil(dt / 2) of the rising
  // (hdr: a positive current loses it) and the falling (hdf: a negative one gains it) dead time the update is
  // computed for, 0 when off
  assign hd_dt  = ev_valley_q ? dt_next_q : dt_q;
  assign hd_dtf = ev_valley_q ? dtf_next_q : dtf_q;

  // a valley update is computed for the period it starts (period_next_q, sampled with it) and the
  // dead time it comes with; a peak update for the active period and dead time (the larger of dt, dtf
  // by the registered flag: one mux level before the adder)
  assign calc_dtx = ev_valley_q ? (dfg_next_q ? dtf_next_q : dt_next_q) : (dfg_q ? dtf_q : dt_q);
  assign calc_mp  = ev_valley_q ? mp_next_q : mp_q;

  always_comb begin
    calc_period_d = calc_period_q;
    calc_thr_d    = calc_thr_q;
    calc_hdr_d    = calc_hdr_q;
    calc_hdf_d    = calc_hdf_q;
    car_ok_d      = car_ok_q;
    if (start_q) begin
      calc_period_d = ev_valley_q ? period_next_q : period_act;
      calc_thr_d    = {1'b0, calc_dtx} + {1'b0, calc_mp};
      calc_hdr_d    = dtc_q ? DtWidth'(({1'b0, hd_dt} + 1'b1) >> 1) : '0;
      calc_hdf_d    = dtc_q ? DtWidth'(({1'b0, hd_dtf} + 1'b1) >> 1) : '0;
      car_ok_d      = vsc_q && calc_period_d == car_per_q;
    end
  end

  // ---- the calculator: reference -> snapped compare values (the modes and features of the build) ----
  logic [3*CntWidth-1:0] snap_cmp;
  logic                  snap_done;

  svpwm_calc #(.Features(Features), .CntWidth(CntWidth), .DtWidth(DtWidth)) u_calc (
    .clk_i      (clk_i),
    .rst_ni     (rst_ni),
    .start_i    (start_q && run_q),
    .abort_i    (!run_q),
    .mode_i     (mode_q),
    .sector_i   (acc_sector),
    .angle_i    (start_q ? acc_angle[PhaseWidth-1 -: 16] : 16'd0),   // read only at start_i; held at 0
                                                                    // otherwise so simulators do not
                                                                    // re-evaluate the calculator every clock
    .theta_i    (s1_q),
    .m_i        (s0_q),
    .fabs_i     (fabs_q),
    .v1_i       (s0_q),
    .v2_i       (s2_q),
    .vf_boost_i (s0_q),
    .vf_slope_i (s1_q),
    .vf_mmax_i  (s2_q),
    .dpwm_i     (dpwm_q),
    .om_i       (om_q),
    // a build without the peak / double update updates at valleys only (start_q implies ev_valley_q): it
    // reads the next-period registers directly, which hold from the sample to the next valley's sample (a
    // whole period > the computation), and with one dead time dt_next_q + mp_next_q; calc_period_q /
    // calc_thr_q are then removed by synthesis (80 LC on the HX1K). Otherwise calc_period_q / calc_thr_q,
    // loaded at the start and valid from the first step on (the programs read them at step 2 at the
    // earliest: model/tests/test_calc_prog.py checks it)
    .period_i   (!HasUpd ? period_next_q : calc_period_q),
    .thr_i      ((!HasUpd && !HasDtf) ? {1'b0, dt_next_q} + {1'b0, mp_next_q} : calc_thr_q),
    .isign_i    (isign_q),
    .hdr_i      (calc_hdr_q),
    .hdf_i      (calc_hdf_q),
    .carry_i    (car_q),                   // (car_q changes only after the computation's done_o)
    .carry_en_i (car_ok_q),
    .busy_o     (duty_busy),
    .done_o     (snap_done),
    .sector_o   (duty_sector),
    .cmp_o      (snap_cmp),
    .sat_o      (duty_sat),
    .err_o      (duty_err),
    .carry_o    (snap_car)
  );

  // ---- shadow and active registers ---------------------------------------------------------------
  logic [3*CntWidth-1:0] cmp_d, cmp_q;
  logic [2:0]            sector_d, sector_q;
  logic                  valid_d, valid_q, sat_d, sat_q, err_d, err_q, update_d, update_q, take;

  // new compare values are taken at a load strobe (the clock before a valley or a peak) exactly when
  // the computation of an update finishes (SampleLead is the pipeline length)
  // (upd_point: load || pre_peak while running, from the carrier's flip-flops, not from run_q)
  assign take = upd_run && pending_q && snap_done && upd_point;

  always_comb begin
    freq_d         = freq_q;
    period_next_d  = period_next_q;
    dt_next_d      = dt_next_q;
    dtf_next_d     = dtf_next_q;
    dfg_next_d     = dfg_next_q;
    mp_next_d      = mp_next_q;
    period_clamp_d = period_clamp_q;
    freq_clamp_d   = freq_clamp_q;
    dt_d           = dt_q;
    dtf_d          = dtf_q;
    dfg_d          = dfg_q;
    mp_d           = mp_q;
    cmp_d          = cmp_q;
    sector_d       = sector_q;
    valid_d        = valid_q;
    sat_d          = sat_q;
    err_d          = err_q;
    update_d       = 1'b0;
    pending_d      = pending_q;
    car_d          = car_q;
    car_per_d      = car_per_q;
    if (!run_q || event_now) begin        // the frequency word steps the angle from the sample on
      freq_d         = freq_clamped;
      freq_clamp_d   = freq_over;
    end
    if (!run_q || vps) begin              // period, dead time, minimum pulse: before every valley
      period_next_d  = period_clamped_q;
      dt_next_d      = dt_use_q;
      dtf_next_d     = dtf_use_q;
      dfg_next_d     = dfg_use_q;
      mp_next_d      = mp_use_q;
      period_clamp_d = period_under_q;
    end
    if (start_q) pending_d = 1'b1;
    if (!upd_run) begin                    // idle: nothing valid, dead time follows the configuration
      dt_d      = dt_use_q;
      dtf_d     = dtf_use_q;
      dfg_d     = dfg_use_q;
      mp_d      = mp_use_q;
      valid_d   = 1'b0;
      pending_d = 1'b0;
    end else begin
      if (load) begin                      // valley: period (in the carrier), dead time, minimum pulse
        dt_d  = dt_next_q;
        dtf_d = dtf_next_q;
        dfg_d = dfg_next_q;
        mp_d  = mp_next_q;
      end
      if (take) begin                      // update point: all three phases together
        cmp_d     = snap_cmp;
        sector_d  = duty_sector;
        sat_d     = duty_sat;
        err_d     = duty_err;
        valid_d   = 1'b1;
        update_d  = 1'b1;
        pending_d = 1'b0;
      end
      if (take_q[1]) begin                 // the calculator's carry_o: valid two clocks after done_o
        car_d     = vsc_q ? snap_car : '0;
        car_per_d = calc_period_q;
      end
    end
    if (!upd_run || trip_sync) car_d = '0; // a stop or a trip: no carry into the next start
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      updv_q         <= 1'b1;
      updp_q         <= 1'b0;
      cz_q           <= 1'b1;
      upd_err_q      <= 1'b0;
      presc_q        <= '0;
      cnt_q          <= '0;
      pl2_q          <= '0;
      vps_q          <= 1'b0;
      pps_q          <= 1'b0;
      start_q        <= 1'b0;
      ev_valley_q    <= 1'b0;
      pending_q      <= 1'b0;
      calc_period_q  <= CntWidth'(MinPeriod);
      calc_thr_q     <= '0;
      calc_hdr_q     <= '0;
      calc_hdf_q     <= '0;
      car_ok_q       <= 1'b0;
      take_q         <= '0;
      car_q          <= '0;
      car_per_q      <= CntWidth'(MinPeriod);
      freq_q         <= '0;
      period_next_q  <= CntWidth'(MinPeriod);
      dt_next_q      <= '0;
      dtf_next_q     <= '0;
      dfg_next_q     <= 1'b0;
      mp_next_q      <= '0;
      period_clamp_q <= 1'b0;
      freq_clamp_q   <= 1'b0;
      dt_q           <= '0;
      dtf_q          <= '0;
      dfg_q          <= 1'b0;
      mp_q           <= '0;
      cmp_q          <= '0;
      sector_q       <= '0;
      valid_q        <= 1'b0;
      sat_q          <= 1'b0;
      err_q          <= 1'b0;
      update_q       <= 1'b0;
    end else begin
      updv_q         <= updv_d;
      updp_q         <= updp_d;
      cz_q           <= cz_d;
      upd_err_q      <= upd_err_d;
      presc_q        <= presc_d;
      cnt_q          <= cnt_d;
      pl2_q          <= pl2_d;
      vps_q          <= vps_d;
      pps_q          <= pps_d;
      start_q        <= run_q && event_now;
      ev_valley_q    <= vps;
      pending_q      <= pending_d;
      calc_period_q  <= calc_period_d;
      calc_thr_q     <= calc_thr_d;
      calc_hdr_q     <= calc_hdr_d;
      calc_hdf_q     <= calc_hdf_d;
      car_ok_q       <= car_ok_d;
      take_q         <= {take_q[0], take};
      car_q          <= car_d;
      car_per_q      <= car_per_d;
      freq_q         <= freq_d;
      period_next_q  <= period_next_d;
      dt_next_q      <= dt_next_d;
      dtf_next_q     <= dtf_next_d;
      dfg_next_q     <= dfg_next_d;
      mp_next_q      <= mp_next_d;
      period_clamp_q <= period_clamp_d;
      freq_clamp_q   <= freq_clamp_d;
      dt_q           <= dt_d;
      dtf_q          <= dtf_d;
      dfg_q          <= dfg_d;
      mp_q           <= mp_d;
      cmp_q          <= cmp_d;
      sector_q       <= sector_d;
      valid_q        <= valid_d;
      sat_q          <= sat_d;
      err_q          <= err_d;
      update_q       <= update_d;
    end
  end

  // ---- comparators and dead time -----------------------------------------------------------------
  logic [2:0] pole;
  logic       pole_valid;

  svpwm_compare #(.CntWidth(CntWidth)) u_compare (
    .clk_i   (clk_i),
    .rst_ni  (rst_ni),
    .run_i   (en_i && run_q && valid_q), // en_i: the poles stop with the gates
    .count_i (count),
    .up_i    (up),
    .cmp_i   (cmp_q),
    .pole_o  (pole),
    .valid_o (pole_valid)
  );

  // trip state as the (synchronous) dead-time FSMs see it: synchronised fault or latched trip
  logic [2:0] hi_req, lo_req;

  assign brake = trip_sync && safe_lo_q;

  // the reset hold (no gate on for 2^DtWidth - 1 clocks after a reset) is the same for the three legs:
  // leg a computes it from its counter (hold_a), legs b and c take it (their hold_o is not read)
  logic hold_a;

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
      .en_i    (trip_sync ? safe_lo_q : (en_i && pole_valid)),   // (pole_valid implies run_q: formal)
      .brake_i (brake),
      .pole_i  (pole[ph]),
      .dt_i    (dt_q),              // deadtime reads them a clock ahead: new dead times and minimum
      .dtf_i   (dtf_act),           // pulse act on the gates from the clock after the valley
      .mp_i    (mp_q),
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
    .cbc_i         (cbc_q),
    .valley_i      (valley),
    .safe_lo_i     (safe_lo_q),
    .pol_i         (pol_q),
    .gate_hi_o     (gate_hi_o),
    .gate_lo_o     (gate_lo_o),
    .fault_o       (fault_o),
    .trip_sync_o   (trip_sync),
    .tripped_o     (tripped_o)
  );

  // ---- current sampling (feature ADC): trigger points and the shunt-window report ------------------
  logic [1:0] adc_pt;

  if (HasAdc) begin : gen_adc
    svpwm_adc #(.CntWidth(CntWidth), .DtWidth(DtWidth)) u_adc (
      .clk_i       (clk_i),
      .rst_ni      (rst_ni),
      .run_i       (run_q),
      .count_i     (count),
      .up_i        (up),
      .valley_i    (valley),
      .peak_i      (peak),
      .period_i    (period_act),
      .sample_i    (event_now),
      .take_i      (take),
      .pt_en_i     (adc_pt_en_i),
      .pt_dn_i     (adc_pt_dn_i),
      .pt_cnt_i    (adc_pt_cnt_i),
      .win_min_i   (win_min_i),
      .active_i    (en_i && run_q && valid_q && !trip_sync),
      .cmp_i       (cmp_q),
      .dt_i        (dt_q),
      .dtf_i       (dtf_act),
      .mp_i        (mp_q),
      .pt_o        (adc_pt),
      .win_lo_o    (win_lo_o),
      .win_hi_o    (win_hi_o),
      .win_ok_o    (win_ok_o),
      .win_recon_o (win_recon_o)
    );
  end else begin : gen_no_adc       // valley / peak triggers only; the points and window inputs not read
    logic unused_adc;
    assign unused_adc  = ^{adc_pt_en_i, adc_pt_dn_i, adc_pt_cnt_i, win_min_i};
    assign adc_pt      = '0;
    assign win_lo_o    = '0;
    assign win_hi_o    = '0;
    assign win_ok_o    = '0;
    assign win_recon_o = '0;
  end

  // the accumulator's low bits set the frequency resolution only; the duty calculator takes the top 16;
  // pre_peak: take reads upd_point (the formal properties read pre_peak)
  logic unused_acc;
  assign unused_acc = ^{acc_angle[PhaseWidth-17:0], duty_busy, fmag[FreqWidth-1], pre_peak};

  assign pole_o         = pole;
  assign carrier_o      = count;
  assign carrier_up_o   = up;
  assign valley_o       = valley;
  assign peak_o         = peak;
  assign update_o       = update_q;
  assign adc_trig_o     = (valley && adc_trig_i[0]) || (peak && adc_trig_i[1]) || adc_pt != 2'b00;
  assign adc_pt_o       = adc_pt;
  assign sync_o         = run_d && load;     // the next clock is a valley (a synced core starts with it)
  assign sector_o       = sector_q;
  assign cmp_o          = cmp_q;
  assign period_o       = period_act;
  assign running_o      = en_i && run_q && valid_q;
  assign sat_o          = sat_q;
  assign cfg_err_o      = err_q || upd_err_q;
  assign period_clamp_o = period_clamp_q;
  assign freq_clamp_o   = freq_clamp_q;
  assign locked_o       = locked_q;

`ifdef FORMAL
  // Core-level properties (formal/core.sby proves them with the duty calculator, phase accumulator and
  // minimum-pulse stage cut: their outputs are free, so these hold whatever compare values arrive).
  logic f_past_valid = 1'b0;
  always_ff @(posedge clk_i) f_past_valid <= 1'b1;
  always_comb if (!f_past_valid) assume (!rst_ni);

  always_comb if (rst_ni) assert (upd_run == run_q);    // the twin run register

  logic f_enabled_q;                                  // the core has run since reset
  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni)   f_enabled_q <= 1'b0;
    else if (run_q)  f_enabled_q <= 1'b1;
  end

  logic [2:0] f_hi, f_lo;                             // gate on/off at the pins, polarity undone
  assign f_hi = gate_hi_o ^ {3{pol_q[0]}};
  assign f_lo = gate_lo_o ^ {3{pol_q[1]}};

  // a leg never has both gates on, at the pins
  always_comb assert ((f_hi & f_lo) == 3'b000);
  // safe state during reset and until enabled: no high side on (low sides only when braking on a trip)
  always_comb if (!rst_ni) assert (f_hi == 3'b000 && f_lo == 3'b000);
  always_comb if (!f_enabled_q) assert (f_hi == 3'b000 && !valid_q && !pole_valid);
  always_comb if (!f_enabled_q && !safe_lo_q) assert (f_lo == 3'b000 || tripped_o == 1'b0);
  // fault asserted => high sides off in the same cycle (and the low sides unless braking)
  always_comb if (fault_i) assert (f_hi == 3'b000);
  always_comb if (fault_i && !safe_lo_q) assert (f_lo == 3'b000);
  // the carrier stays in [0, P] (P is never below MinPeriod once loaded, never 0); compare values,
  // dead time and minimum pulse change only at a load point
  always_comb if (rst_ni) assert (count <= period_act && period_act != '0);
  always_comb if (rst_ni) assert (period_next_q >= CntWidth'(MinPeriod));
  always_ff @(posedge clk_i) if (f_past_valid && $past(rst_ni) && rst_ni) begin
    if (cmp_q != $past(cmp_q)) assert (($past(load) || $past(pre_peak)) && $past(run_q));
    if (dt_q != $past(dt_q) || dtf_act != $past(dtf_act) || mp_q != $past(mp_q)) assert ($past(load));
  end
  // without the update modes the calculator reads period_next_q / dt_next_q + mp_next_q: valley updates only
  // (the update mode stays "valley", so every computation starts from a valley sample)
  always_comb if (!HasUpd && rst_ni) assert (updv_q && !updp_q);
  always_comb if (rst_ni) assert (cz_q == (cnt_q == '0));
  always_comb if (!HasUpd && rst_ni && start_q) assert (ev_valley_q);
  // the poles are valid only while the core runs (the legs' enable reads en_i and pole_valid alone)
  always_comb if (rst_ni && pole_valid) assert (run_q);
  // a locked configuration does not change
  always_ff @(posedge clk_i) if (f_past_valid && $past(rst_ni) && rst_ni && $past(locked_q))
    assert (locked_q && dt_cfg_q == $past(dt_cfg_q) && dtf_cfg_q == $past(dtf_cfg_q) && mp_cfg_q == $past(mp_cfg_q)
            && pol_q == $past(pol_q) && safe_lo_q == $past(safe_lo_q) && cbc_q == $past(cbc_q));
  // not vacuous: gates switch, trips happen and release, compare values load
  always_comb cover (rst_ni && f_hi[0] && running_o);
  always_comb cover (rst_ni && f_lo[1] && running_o && dt_q > DtWidth'(2));
  // asymmetric dead times in force and gates switching (builds with DTF; the others have one dead time);
  // the registered max(dt, dtf) and thresholds are those of the dead times beside them
  if (HasDtf) begin : gen_f_dtf
    function automatic logic [DtWidth:0] f_thr(input logic [DtWidth-1:0] dt, input logic [DtWidth-1:0] dtf,
                                               input logic [DtWidth-1:0] mp);
      f_thr = {1'b0, (dt >= dtf) ? dt : dtf} + {1'b0, mp};
    endfunction
    always_comb if (rst_ni) begin
      assert (dtx_cfg_q == ((dt_cfg_q >= dtf_cfg_q) ? dt_cfg_q : dtf_cfg_q));
      assert (dfg_cfg_q == (dtf_cfg_q > dt_cfg_q) && dfg_use_q == (dtf_use_q > dt_use_q));
      assert (dfg_next_q == (dtf_next_q > dt_next_q) && dfg_q == (dtf_q > dt_q));
      if (start_q) assert (calc_thr_d == f_thr(ev_valley_q ? dt_next_q : dt_q, ev_valley_q ? dtf_next_q : dtf_q,
                                               ev_valley_q ? mp_next_q : mp_q));
    end
    always_comb cover (rst_ni && f_hi[2] && running_o && dt_q > DtWidth'(1) && dtf_q > dt_q && locked_q);
    always_comb cover (rst_ni && f_lo[0] && running_o && dtf_q > DtWidth'(1) && dt_q > dtf_q);
  end
  // ---- issue 27: dead time at the pins across resets and trips. The monitors have no reset
  // (declaration values; they sample rst_ni like any input), so a reset does not make them forget the
  // gate that was on or the dead time in force before it (the core's own dead-time registers are cleared
  // by the reset: F1). f_rel_q: clocks since the release (0 in the release clock), saturating at
  // CntMax + 1; per leg, f_*off_q: clocks the pin has been off before this one, f_*off_dt_q: the other
  // gate's dead time in force in the first clock it was off, f_*off_rst_q: a reset came since it went off.
  // (deadtime reads dt_q / dtf_act a clock ahead: the dead time in force is their value a clock ago.)
  localparam logic [31:0] FW = DtWidth + 1;
  localparam logic [FW-1:0] FSat = {1'b1, {DtWidth{1'b0}}};   // 2^DtWidth = CntMax + 1
  logic [FW-1:0]      f_rel_q = '0;
  logic [DtWidth-1:0] f_dtu_q = '0, f_dtfu_q = '0;
  always_ff @(posedge clk_i) begin
    f_rel_q  <= !rst_ni ? '0 : (f_rel_q >= FSat) ? FSat : f_rel_q + 1'b1;
    f_dtu_q  <= dt_q;
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
      if (f_lo[ph]) f_loff_dt_q <= dt_q;
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
  if (HasUpd) begin : gen_f_f1_cover
    always_ff @(posedge clk_i) if (f_past_valid)
      cover (rst_ni && f_lo[0] && !$past(f_lo[0]) && safe_lo_q && gen_f_leg[0].f_hoff_rst_q && f_hi_ever_q);
  end
  always_ff @(posedge clk_i) cover (f_past_valid && $past(tripped_o) && !tripped_o && running_o);
  always_ff @(posedge clk_i) cover (f_past_valid && rst_ni && cmp_q != $past(cmp_q) && locked_q);
`endif

endmodule

`default_nettype wire
