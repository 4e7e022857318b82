// SPDX-License-Identifier: Apache-2.0
// svpwm_reference: the reference registers of svpwm_core, taken at an update's sample (sample_i: the
// clock before the sample point, svpwm_update) and held for the calculator's computation. Three 16-bit
// slots hold the inputs the mode reads (fixed.input_slots): s0 = m (FREQ, POLAR, invalid) / vf_boost
// (VF) / v1 (AB, DQ), s1 = theta / vf_slope (VF), s2 = v2 / vf_mmax (VF); the calculator's ports of one
// slot share it (a mode never reads two inputs of one slot, and fixed.modulate reads no input its mode
// does not use). The frequency word is clamped to +-FreqMax (freq_clamp_o) and taken at the sample or
// while stopped; it steps the phase accumulator from the sample on. fabs_o = |frequency word| >>
// (FreqWidth - 17) for the V/f law, one clock after the frequency word (the calculator's programs read
// it in step 1 at the earliest, as the operand of step 2: model/tests/test_calc_prog.py checks it).
// Parameters: Features - the build (an input of a feature not built is not read: its register is 0 or
//             not built); FreqWidth, FreqMax as svpwm_core's.
// Latency: one clock (registers), fabs_o two.
`default_nettype none

module svpwm_reference #(
  parameter logic [31:0] Features  = svpwm_pkg::CfgFull,
  parameter int          FreqWidth = 24,
  parameter int          FreqMax   = (1 << (FreqWidth - 1)) - 1
) (
  input  logic                        clk_i,         // core clock
  input  logic                        rst_ni,        // asynchronous reset, active low
  input  logic                        run_i,         // the modulator runs (svpwm_config)
  input  logic                        sample_i,      // take the reference (svpwm_update)
  input  logic [2:0]                  mode_i,        // svpwm_core's reference ports
  input  logic signed [FreqWidth-1:0] freq_i,
  input  logic [15:0]                 m_i,
  input  logic [15:0]                 theta_i,
  input  logic signed [15:0]          v1_i,
  input  logic signed [15:0]          v2_i,
  input  logic [15:0]                 vf_boost_i,
  input  logic [15:0]                 vf_slope_i,
  input  logic [15:0]                 vf_mmax_i,
  input  logic [1:0]                  dpwm_i,
  input  logic                        om_i,
  input  logic                        dtc_en_i,
  input  logic [2:0]                  isign_i,
  input  logic                        vsc_en_i,
  output logic [2:0]                  mode_o,        // the sampled reference
  output logic [15:0]                 s0_o,          // m / vf_boost / v1
  output logic [15:0]                 s1_o,          // theta / vf_slope
  output logic [15:0]                 s2_o,          // v2 / vf_mmax
  output logic [1:0]                  dpwm_o,
  output logic                        om_o,
  output logic                        dtc_o,
  output logic [2:0]                  isign_o,
  output logic                        vsc_o,
  output logic signed [FreqWidth-1:0] freq_o,        // the frequency word, clamped (the accumulator's step)
  output logic [15:0]                 fabs_o,        // |freq_o| >> (FreqWidth - 17)
  output logic                        freq_clamp_o   // |freq_i| > FreqMax was clamped at the last sample
);

  localparam bit HasAcc   = svpwm_pkg::has_acc(Features);      // the phase accumulator
  localparam bit HasVf    = svpwm_pkg::has(Features, svpwm_pkg::FeatVf);
  localparam bit HasXy    = svpwm_pkg::has_xy(Features);
  localparam bit HasDpwm  = svpwm_pkg::has(Features, svpwm_pkg::FeatDpwm);
  localparam bit HasSix   = svpwm_pkg::has(Features, svpwm_pkg::FeatSixstep);
  localparam bit HasDtc   = svpwm_pkg::has(Features, svpwm_pkg::FeatDtc);
  localparam bit HasCarry = svpwm_pkg::has(Features, svpwm_pkg::FeatCarry);

  // ---- the slots and the mode's flags ----------------------------------------------------------------
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
      mode_q  <= '0;
      s0_q    <= '0;
      s1_q    <= '0;
      s2_q    <= '0;
      dpwm_q  <= '0;
      dtc_q   <= 1'b0;
      isign_q <= '0;
      om_q    <= 1'b0;
      vsc_q   <= 1'b0;
    end else if (sample_i) begin
      mode_q  <= mode_i;
      s0_q    <= s0_d;
      s1_q    <= s1_d;
      s2_q    <= s2_d;
      dpwm_q  <= HasDpwm ? dpwm_i : 2'd0;
      dtc_q   <= HasDtc && dtc_en_i;
      isign_q <= HasDtc ? isign_i : 3'd0;
      om_q    <= HasSix && om_i;
      vsc_q   <= HasCarry && vsc_en_i;
    end
  end

  // ---- the frequency word: clamped (bad input gets the nearest legal value and a flag); a build
  // without FREQ and VF has no phase accumulator: freq_i is not read. -(W'(x)), not -W'(x): Yosys 0.70
  // drops a unary operator in front of a size cast (the simulators do not;
  // tb/cocotb/svpwm_core/test_svpwm_core_yosys.py checks the clamp on Yosys' netlist)
  logic signed [FreqWidth-1:0] freq_clamped, freq_d, freq_q;
  logic                        freq_over, freq_clamp_d, freq_clamp_q;
  logic [FreqWidth-1:0]        fmag;
  logic [15:0]                 fabs_d, fabs_q;

  assign freq_over    = HasAcc && (freq_i > FreqWidth'(FreqMax) || freq_i < -(FreqWidth'(FreqMax)));
  assign freq_clamped = !HasAcc ? '0 : !freq_over ? freq_i : freq_i[FreqWidth-1] ? -(FreqWidth'(FreqMax))
                                                                                : FreqWidth'(FreqMax);
  assign freq_d       = (!run_i || sample_i) ? freq_clamped : freq_q;
  assign freq_clamp_d = (!run_i || sample_i) ? freq_over : freq_clamp_q;

  // (freq_q is clamped: no overflow)
  assign fmag = freq_q[FreqWidth-1] ? FreqWidth'(-freq_q) : FreqWidth'(freq_q);
  if (FreqWidth >= 17) begin : gen_fabs_shr
    assign fabs_d = fmag[FreqWidth-2 -: 16];
  end else begin : gen_fabs_shl
    assign fabs_d = 16'({fmag[FreqWidth-2:0], (17 - FreqWidth)'(0)});
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      freq_q       <= '0;
      freq_clamp_q <= 1'b0;
      fabs_q       <= '0;
    end else begin
      freq_q       <= freq_d;
      freq_clamp_q <= freq_clamp_d;
      fabs_q       <= fabs_d;
    end
  end

  logic unused_fmag;
  assign unused_fmag = fmag[FreqWidth-1];

  assign mode_o       = mode_q;
  assign s0_o         = s0_q;
  assign s1_o         = s1_q;
  assign s2_o         = s2_q;
  assign dpwm_o       = dpwm_q;
  assign om_o         = om_q;
  assign dtc_o        = dtc_q;
  assign isign_o      = isign_q;
  assign vsc_o        = vsc_q;
  assign freq_o       = freq_q;
  assign fabs_o       = fabs_q;
  assign freq_clamp_o = freq_clamp_q;

endmodule

`default_nettype wire
