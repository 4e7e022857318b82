// SPDX-License-Identifier: Apache-2.0
// svpwm_core: space-vector PWM core -- frequency + modulation index in, six dead-time-protected gates out.
// Pipeline: phase accumulator (sector + theta') -> sine ROM (0..60 deg) -> multiplier duty calculator
// -> up/down carrier -> three comparators -> dead time per leg -> six registered gate outputs.
// Every carrier period follows Minas Table I / AVR495 Table 4-3: symmetric seven segments, V0 split
// at the start and end, V7 in the middle, one leg switching per transition.
// Parameters:
//   CntWidth   - carrier / period / compare width (8..16)
//   PhaseWidth - in-sector angle fraction bits; f_out = freq * f_clk / (6 * 2^PhaseWidth)
//   FreqWidth  - signed frequency word width (<= PhaseWidth)
//   DtWidth    - dead-time width (max 2^DtWidth - 1 clocks)
//   MinPeriod  - smallest half period accepted; smaller period_i is clamped to it (>= 24)
//   FreqMax    - largest |freq_i| accepted; larger is clamped (default: the full signed range)
//   GatePol    - reset value of the gate polarity {low side, high side}, 1 = active-low pins
// Timing: inputs m_i, period_i, dt_i, mp_i are sampled at the carrier peak, freq_i one clock before
// it (and all continuously while en_i is low). The compare values computed from them (12 + 4 clocks), the new period, dead
// time and minimum pulse all become active together at the next valley. Latency from an input to the
// gates: 0.5 to 1.5 carrier periods (+1 clock to a pole, +1 + dead time to a turned-on gate).
// After en_i rises the gates stay off for the first carrier period (no compare values yet); en_i low
// turns all gates off on the next clock. Reset: all gates off (at the pins, polarity GatePol).
// Safety (README "Safety"): fault_i forces the high sides (and, unless braking, the low sides) off
// combinationally, latched or cycle-by-cycle; a shoot-through interlock is the last stage; the dead
// time, minimum pulse, polarity and safe state are locked by lock_i until reset; out-of-range inputs
// are clamped and flagged, a too short period is lengthened (the dead time is never shortened).
`default_nettype none

module svpwm_core #(
  parameter int CntWidth   = 16,
  parameter int PhaseWidth = 34,
  parameter int FreqWidth  = 24,
  parameter int DtWidth    = 10,
  parameter int MinPeriod  = 32,
  parameter int FreqMax    = (1 << (FreqWidth - 1)) - 1,
  parameter logic [1:0] GatePol = 2'b00
) (
  input  logic                        clk_i,           // core clock (default 48 MHz)
  input  logic                        rst_ni,          // asynchronous reset, active low
  input  logic                        en_i,            // run: 1 modulate, 0 all gates off
  input  logic signed [FreqWidth-1:0] freq_i,          // frequency word, signed (negative = reverse)
  input  logic [15:0]                 m_i,             // modulation index UQ1.15, 0x8000 = 1.0
  input  logic [CntWidth-1:0]         period_i,        // half carrier period in clocks
  input  logic [DtWidth-1:0]          dt_i,            // dead time in clocks (locked by lock_i)
  input  logic [DtWidth-1:0]          mp_i,            // minimum gate pulse in clocks (locked)
  input  logic                        fault_i,         // trip input, asynchronous, active high
  input  logic                        fault_clear_i,   // clears a latched trip once fault_i is low
  input  logic                        trip_cbc_i,      // trip mode: 0 latched, 1 cycle-by-cycle (locked)
  input  logic                        safe_lo_i,       // safe state: 0 all off, 1 low sides on (locked)
  input  logic [1:0]                  pol_i,           // {lo, hi} pin polarity, 1 = active low (locked;
                                                       // taken only while en_i is low)
  input  logic                        lock_i,          // locks dt, mp, safe state, trip mode, polarity
  output logic [2:0]                  gate_hi_o,       // {c, b, a} high-side gate pins (polarity applied)
  output logic [2:0]                  gate_lo_o,       // {c, b, a} low-side gate pins (polarity applied)
  output logic [2:0]                  pole_o,          // {c, b, a} modulator states before dead time
  output logic [CntWidth-1:0]         carrier_o,       // carrier value 0..P
  output logic                        carrier_up_o,    // carrier counting up
  output logic                        valley_o,        // pulse: first clock of a carrier period
  output logic                        peak_o,          // pulse: carrier peak (inputs sampled here)
  output logic [2:0]                  sector_o,        // sector (0..5 = seeds' 1..6) of the active period
  output logic [3*CntWidth-1:0]       cmp_o,           // {C_c, C_b, C_a} of the active period
  output logic [CntWidth-1:0]         period_o,        // active half period
  output logic                        running_o,       // compare values valid, gates modulating
  output logic                        m_clamp_o,       // m_i > 1.0 was clamped at the last sample
  output logic                        period_clamp_o,  // period_i too short was lengthened at the last sample
  output logic                        freq_clamp_o,    // |freq_i| > FreqMax was clamped at the last sample
  output logic                        fault_o,         // fault_i, synchronised
  output logic                        tripped_o,       // safe state forced (fault_i or latched trip)
  output logic                        locked_o         // configuration locked until reset
);

`ifdef FORMAL
  localparam int MinPeriodFloor = 4;    // formal/core.sby cuts the compute pipeline: no latency to cover
`else
  localparam int MinPeriodFloor = 24;   // duty calculator 12 + minimum pulse 4 + load margin
`endif
  if (MinPeriod < MinPeriodFloor || MinPeriod >= (1 << CntWidth)) begin : gen_bad_min_period
    initial $fatal(1, "svpwm_core: MinPeriod must be >= 24 (compute latency 17 + margin), got %0d",
                   MinPeriod);
  end
  if (DtWidth + 2 > CntWidth) begin : gen_bad_dt_width
    initial $fatal(1, "svpwm_core: need DtWidth + 2 <= CntWidth (period >= 2 (dt + mp)), got %0d / %0d",
                   DtWidth, CntWidth);
  end
  if (FreqMax < 1 || FreqMax > (1 << (FreqWidth - 1)) - 1) begin : gen_bad_freq_max
    initial $fatal(1, "svpwm_core: FreqMax must be 1..2^(FreqWidth-1)-1, got %0d", FreqMax);
  end

  // ---- run: en_i, but not in the first three clocks after reset, so that the configuration
  // registers, the lowest legal period and then the idle loads (period clamped for the dead time,
  // frequency) all happen before the carrier starts -----------------------------------------------
  logic [2:0] armed_q;
  logic       run;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) armed_q <= '0;
    else         armed_q <= {armed_q[1:0], 1'b1};
  end

  assign run = en_i && armed_q[2];

  // ---- configuration registers, locked by lock_i until reset ----------------------------------
  logic               locked_q;
  logic [DtWidth-1:0] dt_cfg_q, mp_cfg_q;
  logic               cbc_q, safe_lo_q;
  logic [1:0]         pol_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      locked_q  <= 1'b0;
      dt_cfg_q  <= '0;
      mp_cfg_q  <= '0;
      cbc_q     <= 1'b0;
      safe_lo_q <= 1'b0;
      pol_q     <= GatePol;
    end else begin
      if (lock_i) locked_q <= 1'b1;
      if (!locked_q) begin
        dt_cfg_q  <= dt_i;
        mp_cfg_q  <= mp_i;
        cbc_q     <= trip_cbc_i;
        safe_lo_q <= safe_lo_i;
        if (!run) pol_q <= pol_i;
      end
    end
  end

  // ---- input clamps (bad input gets the nearest legal value and a flag) --------------------------
  localparam logic [15:0] MOne = 16'h8000;

  logic [15:0]                 m_clamped;
  logic [CntWidth-1:0]         period_clamped, period_low;
  logic [DtWidth:0]            thr;             // dead time + minimum pulse
  logic signed [FreqWidth-1:0] freq_clamped;
  logic                        m_over, period_under, freq_over;

  assign m_over         = m_i > MOne;
  assign m_clamped      = m_over ? MOne : m_i;
  assign thr            = {1'b0, dt_cfg_q} + {1'b0, mp_cfg_q};
  assign period_low     = (CntWidth'({thr, 1'b0}) > CntWidth'(MinPeriod)) ? CntWidth'({thr, 1'b0})
                                                                        : CntWidth'(MinPeriod);

  // the lowest legal period is registered (off the sampling paths); dt / mp are used one clock later
  // too (dt_use_q / mp_use_q), so a period is always clamped for the dead time it is used with
  logic [CntWidth-1:0] period_low_q;
  logic [DtWidth-1:0]  dt_use_q, mp_use_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      period_low_q <= CntWidth'(MinPeriod);
      dt_use_q     <= '0;
      mp_use_q     <= '0;
    end else begin
      period_low_q <= period_low;
      dt_use_q     <= dt_cfg_q;
      mp_use_q     <= mp_cfg_q;
    end
  end

  assign period_under   = period_i < period_low_q;
  assign period_clamped = period_under ? period_low_q : period_i;

  assign freq_over      = freq_i > FreqWidth'(FreqMax) || freq_i < -FreqWidth'(FreqMax);
  assign freq_clamped   = !freq_over ? freq_i : freq_i[FreqWidth-1] ? -FreqWidth'(FreqMax)
                                                                     : FreqWidth'(FreqMax);

  // ---- carrier -----------------------------------------------------------------------------------
  logic [CntWidth-1:0] count, period_act;
  logic                up, valley, peak, pre_peak, load, sample;

  logic [CntWidth-1:0] period_next_d, period_next_q;
  logic [DtWidth-1:0]  dt_next_d, dt_next_q, dt_d, dt_q, mp_next_d, mp_next_q, mp_d, mp_q;
  logic signed [FreqWidth-1:0] freq_d, freq_q;
  logic                m_clamp_d, m_clamp_q, period_clamp_d, period_clamp_q, freq_clamp_d, freq_clamp_q;

  svpwm_carrier #(.CntWidth(CntWidth)) u_carrier (
    .clk_i    (clk_i),
    .rst_ni   (rst_ni),
    .run_i    (run),
    .period_i (run ? period_next_q : period_clamped),
    .count_o  (count),
    .up_o     (up),
    .period_o (period_act),
    .valley_o (valley),
    .peak_o     (peak),
    .pre_peak_o (pre_peak),
    .load_o     (load)
  );

  assign sample = peak;   // inputs are sampled at the peak; idle cycles load them directly

  // ---- phase accumulator -------------------------------------------------------------------------
  logic [2:0]            acc_sector;
  logic [PhaseWidth-1:0] acc_angle;

  svpwm_phase_acc #(.PhaseWidth(PhaseWidth), .FreqWidth(FreqWidth)) u_phase (
    .clk_i    (clk_i),
    .rst_ni   (rst_ni),
    .run_i    (run),
    .step_i   (freq_q),             // switched at the peak: loaded on the clock before it
    .sector_o (acc_sector),
    .angle_o  (acc_angle)
  );

  // ---- duty calculator ---------------------------------------------------------------------------
  logic [2:0]            duty_sector;
  logic [3*CntWidth-1:0] duty_cmp;
  logic                  duty_done, duty_busy;

  svpwm_duty #(.CntWidth(CntWidth)) u_duty (
    .clk_i    (clk_i),
    .rst_ni   (rst_ni),
    .start_i  (sample),
    .sector_i (acc_sector),
    .angle_i  (acc_angle[PhaseWidth-1 -: 16]),
    .m_i      (m_clamped),
    .period_i (period_clamped),
    .busy_o   (duty_busy),
    .done_o   (duty_done),
    .sector_o (duty_sector),
    .cmp_o    (duty_cmp)
  );

  // ---- minimum pulse -----------------------------------------------------------------------------
  logic [3*CntWidth-1:0] snap_cmp;
  logic                  snap_done;
  logic [2:0]            snap_sector_q;

  svpwm_minpulse #(.CntWidth(CntWidth), .DtWidth(DtWidth)) u_minpulse (
    .clk_i    (clk_i),
    .rst_ni   (rst_ni),
    .start_i  (duty_done),
    .cmp_i    (duty_cmp),
    .period_i (period_next_q),
    .thr_i    ({1'b0, dt_next_q} + {1'b0, mp_next_q}),
    .done_o   (snap_done),
    .cmp_o    (snap_cmp)
  );

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni)        snap_sector_q <= '0;
    else if (duty_done) snap_sector_q <= duty_sector;
  end

  // ---- shadow and active registers ---------------------------------------------------------------
  logic [3*CntWidth-1:0] cmp_d, cmp_q;
  logic [2:0]            sector_d, sector_q;
  logic                  result_d, result_q, valid_d, valid_q;

  always_comb begin
    freq_d         = freq_q;
    period_next_d  = period_next_q;
    dt_next_d      = dt_next_q;
    mp_next_d      = mp_next_q;
    m_clamp_d      = m_clamp_q;
    period_clamp_d = period_clamp_q;
    freq_clamp_d   = freq_clamp_q;
    dt_d           = dt_q;
    mp_d           = mp_q;
    cmp_d          = cmp_q;
    sector_d       = sector_q;
    result_d       = result_q;
    valid_d        = valid_q;
    if (!run || pre_peak) begin           // the frequency word is taken one clock before the peak, so
      freq_d         = freq_clamped;       // it steps the angle from the peak on (off the adder path)
      freq_clamp_d   = freq_over;
    end
    if (!run || sample) begin             // sample point
      period_next_d  = period_clamped;
      dt_next_d      = dt_use_q;
      mp_next_d      = mp_use_q;
      m_clamp_d      = m_over;
      period_clamp_d = period_under;
    end
    if (snap_done) result_d = 1'b1;        // a result waits for the next valley
    if (!run) begin                        // idle: nothing valid, dead time follows the configuration
      dt_d     = dt_use_q;
      mp_d     = mp_use_q;
      result_d = 1'b0;
      valid_d  = 1'b0;
    end else if (load) begin               // load point: all three phases, period, dt and mp together
      dt_d     = dt_next_q;
      mp_d     = mp_next_q;
      cmp_d    = snap_cmp;
      sector_d = snap_sector_q;
      valid_d  = result_q;
      result_d = 1'b0;
    end
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      freq_q         <= '0;
      period_next_q  <= CntWidth'(MinPeriod);
      dt_next_q      <= '0;
      mp_next_q      <= '0;
      m_clamp_q      <= 1'b0;
      period_clamp_q <= 1'b0;
      freq_clamp_q   <= 1'b0;
      dt_q           <= '0;
      mp_q           <= '0;
      cmp_q          <= '0;
      sector_q       <= '0;
      result_q       <= 1'b0;
      valid_q        <= 1'b0;
    end else begin
      freq_q         <= freq_d;
      period_next_q  <= period_next_d;
      dt_next_q      <= dt_next_d;
      mp_next_q      <= mp_next_d;
      m_clamp_q      <= m_clamp_d;
      period_clamp_q <= period_clamp_d;
      freq_clamp_q   <= freq_clamp_d;
      dt_q           <= dt_d;
      mp_q           <= mp_d;
      cmp_q          <= cmp_d;
      sector_q       <= sector_d;
      result_q       <= result_d;
      valid_q        <= valid_d;
    end
  end

  // ---- comparators and dead time -----------------------------------------------------------------
  logic [2:0] pole;
  logic       pole_valid;

  svpwm_compare #(.CntWidth(CntWidth)) u_compare (
    .clk_i   (clk_i),
    .rst_ni  (rst_ni),
    .run_i   (run && valid_q),
    .count_i (count),
    .up_i    (up),
    .cmp_i   (cmp_q),
    .pole_o  (pole),
    .valid_o (pole_valid)
  );

  // trip state as the (synchronous) dead-time FSMs see it: synchronised fault or latched trip
  logic       trip_sync, brake;
  logic [2:0] hi_req, lo_req;

  assign brake = trip_sync && safe_lo_q;

  for (genvar ph = 0; ph < 3; ph++) begin : gen_leg
    deadtime #(.DtWidth(DtWidth)) u_deadtime (
      .clk_i   (clk_i),
      .rst_ni  (rst_ni),
      .en_i    (trip_sync ? safe_lo_q : (run && pole_valid)),
      .brake_i (brake),
      .pole_i  (pole[ph]),
      .dt_i    (dt_q),
      .mp_i    (mp_q),
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

  // the accumulator's low bits set the frequency resolution only; the duty calculator takes the top 16
  logic unused_acc;
  assign unused_acc = ^{acc_angle[PhaseWidth-17:0], duty_busy};

  assign pole_o         = pole;
  assign carrier_o      = count;
  assign carrier_up_o   = up;
  assign valley_o       = valley;
  assign peak_o         = peak;
  assign sector_o       = sector_q;
  assign cmp_o          = cmp_q;
  assign period_o       = period_act;
  assign running_o      = run && valid_q;
  assign m_clamp_o      = m_clamp_q;
  assign period_clamp_o = period_clamp_q;
  assign freq_clamp_o   = freq_clamp_q;
  assign locked_o       = locked_q;

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
    if (cmp_q != $past(cmp_q)) assert ($past(load) && $past(run));
    if (dt_q != $past(dt_q) || mp_q != $past(mp_q)) assert ($past(load));
  end
  // a locked configuration does not change
  always_ff @(posedge clk_i) if (f_past_valid && $past(rst_ni) && rst_ni && $past(locked_q))
    assert (locked_q && dt_cfg_q == $past(dt_cfg_q) && mp_cfg_q == $past(mp_cfg_q)
            && pol_q == $past(pol_q) && safe_lo_q == $past(safe_lo_q) && cbc_q == $past(cbc_q));
  // not vacuous: gates switch, trips happen and release, compare values load
  always_comb cover (rst_ni && f_hi[0] && running_o);
  always_comb cover (rst_ni && f_lo[1] && running_o && dt_q > DtWidth'(2));
  always_ff @(posedge clk_i) cover (f_past_valid && $past(tripped_o) && !tripped_o && running_o);
  always_ff @(posedge clk_i) cover (f_past_valid && rst_ni && cmp_q != $past(cmp_q) && locked_q);
`endif

endmodule

`default_nettype wire
