// SPDX-License-Identifier: Apache-2.0
// svpwm_bench_top: out-of-context wrapper for the synthesis benchmark (scripts/synth_bench.py).
// The core's input bits come from a shift register (sdi_i shifted in while shift_i is high) so
// that they are driven by flip-flops like in a real system without 67 pins; the gates and the status
// outputs go to pins. The core's debug outputs (carrier, compare values, period) are left open, as
// in a board design. Overhead over the core alone: the flip-flops of the shift register, one
// logic cell each -- synth_bench.py subtracts them (wrapper_lc) to give the core's own count.
`default_nettype none

module svpwm_bench_top #(
  parameter logic [31:0] Features = svpwm_pkg::CfgFull,   // svpwm_core's build (the inputs it does not
                                               // read stay in the shift register: wrapper_lc is the same)
  parameter int CntWidth   = 16,
  parameter int PhaseWidth = 34,
  parameter int FreqWidth  = 24,
  parameter int DtWidth    = 10,
  parameter int MinPeriod  = svpwm_pkg::min_period(Features)
) (
  input  wire        clk_i,
  input  wire        rst_ni,
  input  wire        sdi_i,
  input  wire        shift_i,
  output logic [2:0] gate_hi_o,
  output logic [2:0] gate_lo_o,
  output logic [2:0] sector_o,
  output logic       running_o,
  output logic       sat_o,
  output logic       period_clamp_o,
  output logic       cfg_err_o,
  output logic       adc_trig_o,
  output logic       update_o,
  output logic       win_sdo_o      // builds with ADC: the shunt-window report, shifted out (else 0)
);
  localparam int B   = 1 + FreqWidth + 16 + CntWidth + DtWidth;   // first safety input bit
  localparam int R   = B + DtWidth + 7;                          // first input-mode bit
  localparam int F   = R + 3 + 6 * 16 + 2 + 2 + 8 + 2 + 2 + 6;     // falling dead time, its enable
  localparam int A   = F + DtWidth + 1;                          // ADC points, minimum window (last:
  localparam int NIn = A + 3 * CntWidth + 5;                     // unread, so removed, without ADC)
  localparam bit HasAdc = svpwm_pkg::has(Features, svpwm_pkg::FeatAdc);
  localparam int NOut = 6 * (CntWidth + 1) + 5;                  // the window report

  logic [NIn-1:0] in_q;
  always_ff @(posedge clk_i) begin
    if (shift_i) in_q <= {in_q[NIn-2:0], sdi_i};
  end

  // the window report leaves through an output shift register (loaded while shift_i is low), so that
  // synthesis keeps it as a reader would: one logic cell per bit, subtracted like the input register
  logic [NOut-1:0] win;
  if (HasAdc) begin : gen_win_out
    logic [NOut-1:0] out_q;
    always_ff @(posedge clk_i) begin
      out_q <= shift_i ? {out_q[NOut-2:0], 1'b0} : win;
    end
    assign win_sdo_o = out_q[NOut-1];
  end else begin : gen_no_win_out
    logic unused_win;
    assign unused_win = ^win;
    assign win_sdo_o  = 1'b0;
  end

  svpwm_core #(
    .Features   (Features),
    .CntWidth   (CntWidth),
    .PhaseWidth (PhaseWidth),
    .FreqWidth  (FreqWidth),
    .DtWidth    (DtWidth),
    .MinPeriod  (MinPeriod)
  ) u_core (
    .clk_i          (clk_i),
    .rst_ni         (rst_ni),
    .en_i           (in_q[0]),
    .mode_i         (in_q[R +: 3]),
    .freq_i         (in_q[1 +: FreqWidth]),
    .m_i            (in_q[1 + FreqWidth +: 16]),
    .theta_i        (in_q[R + 3 +: 16]),
    .v1_i           (in_q[R + 19 +: 16]),
    .v2_i           (in_q[R + 35 +: 16]),
    .vf_boost_i     (in_q[R + 51 +: 16]),
    .vf_slope_i     (in_q[R + 67 +: 16]),
    .vf_mmax_i      (in_q[R + 83 +: 16]),
    .dpwm_i         (in_q[R + 99 +: 2]),
    .upd_i          (in_q[R + 101 +: 2]),
    .presc_i        (in_q[R + 103 +: 8]),
    .adc_trig_i     (in_q[R + 111 +: 2]),
    .adc_pt_en_i    (in_q[A +: 2]),
    .adc_pt_dn_i    (in_q[A + 2 +: 2]),
    .adc_pt_cnt_i   (in_q[A + 4 +: 2 * CntWidth]),
    .win_min_i      (in_q[A + 4 + 2 * CntWidth +: CntWidth + 1]),
    .sync_en_i      (in_q[R + 113]),
    .sync_i         (in_q[R + 114]),
    .dtc_en_i       (in_q[R + 115]),
    .isign_i        (in_q[R + 116 +: 3]),
    .om_i           (in_q[R + 119]),
    .vsc_en_i       (in_q[R + 120]),
    .period_i       (in_q[1 + FreqWidth + 16 +: CntWidth]),
    .dt_i           (in_q[1 + FreqWidth + 16 + CntWidth +: DtWidth]),
    .dtf_i          (in_q[F +: DtWidth]),
    .dtf_en_i       (in_q[F + DtWidth]),
    .mp_i           (in_q[B +: DtWidth]),
    .fault_i        (in_q[B + DtWidth]),
    .fault_clear_i  (in_q[B + DtWidth + 1]),
    .trip_cbc_i     (in_q[B + DtWidth + 2]),
    .safe_lo_i      (in_q[B + DtWidth + 3]),
    .pol_i          (in_q[B + DtWidth + 4 +: 2]),
    .lock_i         (in_q[B + DtWidth + 6]),
    .gate_hi_o      (gate_hi_o),
    .gate_lo_o      (gate_lo_o),
    .pole_o         (),
    .carrier_o      (),
    .carrier_up_o   (),
    .valley_o       (),
    .peak_o         (),
    .update_o       (update_o),
    .adc_trig_o     (adc_trig_o),
    .adc_pt_o       (),
    .win_lo_o       (win[0 +: 3 * (CntWidth + 1)]),
    .win_hi_o       (win[3 * (CntWidth + 1) +: 3 * (CntWidth + 1)]),
    .win_ok_o       (win[6 * (CntWidth + 1) +: 3]),
    .win_recon_o    (win[6 * (CntWidth + 1) + 3 +: 2]),
    .sync_o         (),
    .sector_o       (sector_o),
    .cmp_o          (),
    .period_o       (),
    .running_o      (running_o),
    .sat_o          (sat_o),
    .cfg_err_o      (cfg_err_o),
    .period_clamp_o (period_clamp_o),
    .freq_clamp_o   (),
    .fault_o        (),
    .tripped_o      (),
    .locked_o       ()
  );
endmodule

`default_nettype wire
