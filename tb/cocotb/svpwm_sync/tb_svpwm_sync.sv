// SPDX-License-Identifier: Apache-2.0
// tb_svpwm_sync: two svpwm_core instances on one clock for the multi-axis sync and ADC-trigger tests.
// The master's sync_o drives the slave's sync_i; both take the same reference and configuration.
`timescale 1ns / 1ps
`default_nettype none

module tb_svpwm_sync (
  input  logic                rst_ni,
  input  logic                en_m_i,         // master run
  input  logic                en_s_i,         // slave run
  input  logic                sync_en_s_i,    // slave waits for the master's sync_o
  input  logic [15:0]         period_i,
  input  logic [15:0]         m_i,
  input  logic signed [23:0]  freq_i,
  input  logic [1:0]          adc_trig_i,     // master's ADC trigger selection
  output logic                clk,
  output logic [15:0]         carrier_m_o,
  output logic [15:0]         carrier_s_o,
  output logic                valley_m_o,
  output logic                peak_m_o,
  output logic                valley_s_o,
  output logic                adc_trig_m_o,
  output logic                sync_m_o,
  output logic                running_s_o,
  output logic [2:0]          gate_hi_s_o,
  output logic [2:0]          gate_lo_s_o
);

  initial clk = 1'b0;
  always #5 clk = ~clk;

  logic [2:0] unused_hi_m, unused_lo_m;

  svpwm_core u_master (
    .clk_i (clk), .rst_ni (rst_ni), .en_i (en_m_i), .mode_i (3'd0), .freq_i (freq_i), .m_i (m_i),
    .theta_i ('0), .v1_i ('0), .v2_i ('0), .vf_boost_i ('0), .vf_slope_i ('0), .vf_mmax_i ('0),
    .dpwm_i (2'd0), .upd_i (2'd0), .presc_i ('0), .period_i (period_i), .dt_i (10'd5), .dtf_i ('0), .dtf_en_i (1'b0), .mp_i ('0),
    .adc_pt_en_i (2'b00), .adc_pt_dn_i (2'b00), .adc_pt_cnt_i ('0), .win_min_i ('0),
    .adc_trig_i (adc_trig_i), .om_i (1'b0), .vsc_en_i (1'b0), .dtc_en_i (1'b0), .isign_i (3'd0), .sync_en_i (1'b0), .sync_i (1'b0), .fault_i (1'b0),
    .fault_clear_i (1'b0), .trip_cbc_i (1'b0), .safe_lo_i (1'b0), .pol_i (2'b00), .lock_i (1'b0),
    .gate_hi_o (unused_hi_m), .gate_lo_o (unused_lo_m), .pole_o (), .carrier_o (carrier_m_o),
    .carrier_up_o (), .valley_o (valley_m_o), .peak_o (peak_m_o), .update_o (),
    .adc_pt_o (), .win_lo_o (), .win_hi_o (), .win_ok_o (), .win_recon_o (),
    .adc_trig_o (adc_trig_m_o), .sync_o (sync_m_o), .sector_o (), .cmp_o (), .period_o (),
    .running_o (), .sat_o (), .cfg_err_o (), .period_clamp_o (), .freq_clamp_o (), .fault_o (),
    .tripped_o (), .locked_o ()
  );

  svpwm_core u_slave (
    .clk_i (clk), .rst_ni (rst_ni), .en_i (en_s_i), .mode_i (3'd0), .freq_i (freq_i), .m_i (m_i),
    .theta_i ('0), .v1_i ('0), .v2_i ('0), .vf_boost_i ('0), .vf_slope_i ('0), .vf_mmax_i ('0),
    .dpwm_i (2'd0), .upd_i (2'd0), .presc_i ('0), .period_i (period_i), .dt_i (10'd5), .dtf_i ('0), .dtf_en_i (1'b0), .mp_i ('0),
    .adc_pt_en_i (2'b00), .adc_pt_dn_i (2'b00), .adc_pt_cnt_i ('0), .win_min_i ('0),
    .adc_trig_i (2'b00), .om_i (1'b0), .vsc_en_i (1'b0), .dtc_en_i (1'b0), .isign_i (3'd0), .sync_en_i (sync_en_s_i), .sync_i (sync_m_o), .fault_i (1'b0),
    .fault_clear_i (1'b0), .trip_cbc_i (1'b0), .safe_lo_i (1'b0), .pol_i (2'b00), .lock_i (1'b0),
    .gate_hi_o (gate_hi_s_o), .gate_lo_o (gate_lo_s_o), .pole_o (), .carrier_o (carrier_s_o),
    .adc_pt_o (), .win_lo_o (), .win_hi_o (), .win_ok_o (), .win_recon_o (),
    .carrier_up_o (), .valley_o (valley_s_o), .peak_o (), .update_o (), .adc_trig_o (), .sync_o (),
    .sector_o (), .cmp_o (), .period_o (), .running_o (running_s_o), .sat_o (), .cfg_err_o (),
    .period_clamp_o (), .freq_clamp_o (), .fault_o (), .tripped_o (), .locked_o ()
  );

endmodule

`default_nettype wire
