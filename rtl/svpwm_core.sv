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
//   MinPeriod  - smallest half period accepted; smaller period_i is clamped to it (>= 16)
// Timing: inputs freq_i, m_i, period_i, dt_i are sampled at the carrier peak (and continuously while
// en_i is low). The compare values computed from them (11 clocks), the new period and the new dead
// time all become active together at the next valley. Latency from an input to the gates: from
// 0.5 to 1.5 carrier periods (+1 clock to a pole, +1 + dead time to a turned-on gate).
// After en_i rises the gates stay off for the first carrier period (no compare values yet); en_i low
// turns all gates off on the next clock. Reset: all gates off.
// Restrictions: dead time below half the period is the caller's job in this version.
`default_nettype none

module svpwm_core #(
  parameter int CntWidth   = 16,
  parameter int PhaseWidth = 34,
  parameter int FreqWidth  = 24,
  parameter int DtWidth    = 10,
  parameter int MinPeriod  = 32
) (
  input  logic                        clk_i,           // core clock (default 48 MHz)
  input  logic                        rst_ni,          // asynchronous reset, active low
  input  logic                        en_i,            // run: 1 modulate, 0 all gates off
  input  logic signed [FreqWidth-1:0] freq_i,          // frequency word, signed (negative = reverse)
  input  logic [15:0]                 m_i,             // modulation index UQ1.15, 0x8000 = 1.0
  input  logic [CntWidth-1:0]         period_i,        // half carrier period in clocks
  input  logic [DtWidth-1:0]          dt_i,            // dead time in clocks
  output logic [2:0]                  gate_hi_o,       // {c, b, a} high-side gates, 1 = on
  output logic [2:0]                  gate_lo_o,       // {c, b, a} low-side gates, 1 = on
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
  output logic                        period_clamp_o   // period_i < MinPeriod was clamped at the last sample
);

  if (MinPeriod < 16 || MinPeriod >= (1 << CntWidth)) begin : gen_bad_min_period
    initial $fatal(1, "svpwm_core: MinPeriod must be >= 16 (duty latency 11 + margin), got %0d", MinPeriod);
  end

  // ---- input clamps ------------------------------------------------------------------------------
  localparam logic [15:0] MOne = 16'h8000;

  logic [15:0]         m_clamped;
  logic [CntWidth-1:0] period_clamped;
  logic                m_over, period_under;

  assign m_over         = m_i > MOne;
  assign m_clamped      = m_over ? MOne : m_i;
  assign period_under   = period_i < CntWidth'(MinPeriod);
  assign period_clamped = period_under ? CntWidth'(MinPeriod) : period_i;

  // ---- carrier -----------------------------------------------------------------------------------
  logic [CntWidth-1:0] count, period_act;
  logic                up, valley, peak, load, sample;

  logic [CntWidth-1:0] period_next_d, period_next_q;
  logic [DtWidth-1:0]  dt_next_d, dt_next_q, dt_d, dt_q;
  logic signed [FreqWidth-1:0] freq_d, freq_q;
  logic                m_clamp_d, m_clamp_q, period_clamp_d, period_clamp_q;

  svpwm_carrier #(.CntWidth(CntWidth)) u_carrier (
    .clk_i    (clk_i),
    .rst_ni   (rst_ni),
    .run_i    (en_i),
    .period_i (en_i ? period_next_q : period_clamped),
    .count_o  (count),
    .up_o     (up),
    .period_o (period_act),
    .valley_o (valley),
    .peak_o   (peak),
    .load_o   (load)
  );

  assign sample = peak;   // inputs are sampled at the peak; idle cycles load them directly

  // ---- phase accumulator -------------------------------------------------------------------------
  logic [2:0]            acc_sector;
  logic [PhaseWidth-1:0] acc_angle;

  svpwm_phase_acc #(.PhaseWidth(PhaseWidth), .FreqWidth(FreqWidth)) u_phase (
    .clk_i    (clk_i),
    .rst_ni   (rst_ni),
    .run_i    (en_i),
    .step_i   (sample ? freq_i : freq_q),
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

  // ---- shadow and active registers ---------------------------------------------------------------
  logic [3*CntWidth-1:0] cmp_d, cmp_q;
  logic [2:0]            sector_d, sector_q;
  logic                  result_d, result_q, valid_d, valid_q;

  always_comb begin
    freq_d         = freq_q;
    period_next_d  = period_next_q;
    dt_next_d      = dt_next_q;
    m_clamp_d      = m_clamp_q;
    period_clamp_d = period_clamp_q;
    dt_d           = dt_q;
    cmp_d          = cmp_q;
    sector_d       = sector_q;
    result_d       = result_q;
    valid_d        = valid_q;
    if (!en_i || sample) begin             // sample point
      freq_d         = freq_i;
      period_next_d  = period_clamped;
      dt_next_d      = dt_i;
      m_clamp_d      = m_over;
      period_clamp_d = period_under;
    end
    if (duty_done) result_d = 1'b1;        // a result waits for the next valley
    if (!en_i) begin                       // idle: nothing valid, dead time follows the input
      dt_d     = dt_i;
      result_d = 1'b0;
      valid_d  = 1'b0;
    end else if (load) begin               // load point: all three phases, period and dead time together
      dt_d     = dt_next_q;
      cmp_d    = duty_cmp;
      sector_d = duty_sector;
      valid_d  = result_q;
      result_d = 1'b0;
    end
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      freq_q         <= '0;
      period_next_q  <= CntWidth'(MinPeriod);
      dt_next_q      <= '0;
      m_clamp_q      <= 1'b0;
      period_clamp_q <= 1'b0;
      dt_q           <= '0;
      cmp_q          <= '0;
      sector_q       <= '0;
      result_q       <= 1'b0;
      valid_q        <= 1'b0;
    end else begin
      freq_q         <= freq_d;
      period_next_q  <= period_next_d;
      dt_next_q      <= dt_next_d;
      m_clamp_q      <= m_clamp_d;
      period_clamp_q <= period_clamp_d;
      dt_q           <= dt_d;
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
    .run_i   (en_i && valid_q),
    .count_i (count),
    .up_i    (up),
    .cmp_i   (cmp_q),
    .pole_o  (pole),
    .valid_o (pole_valid)
  );

  for (genvar ph = 0; ph < 3; ph++) begin : gen_leg
    deadtime #(.DtWidth(DtWidth)) u_deadtime (
      .clk_i  (clk_i),
      .rst_ni (rst_ni),
      .en_i   (en_i && pole_valid),
      .pole_i (pole[ph]),
      .dt_i   (dt_q),
      .hi_o   (gate_hi_o[ph]),
      .lo_o   (gate_lo_o[ph])
    );
  end

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
  assign running_o      = en_i && valid_q;
  assign m_clamp_o      = m_clamp_q;
  assign period_clamp_o = period_clamp_q;

endmodule

`default_nettype wire
