// SPDX-License-Identifier: Apache-2.0
// tb_core_bench: raw simulation throughput of the full core in the regression harness (tb_svpwm_core:
// SV clock, the per-clock pin checker), without cocotb: constant inputs (Minas Fig. 10: 50 Hz, m = 0.9,
// P = 1536, 1 us dead time at 48 MHz), +clocks=<n> clocks after enabling, then the checker's counters.
// scripts/bench.py builds it with Verilator (--binary) and Icarus and times the run (`make bench`).
`timescale 1ns / 1ps
`default_nettype none
module tb_core_bench;
  logic        rst_ni = 1'b0, en_i = 1'b0;
  logic        clk;
  longint unsigned clocks = 64'd1_000_000;
  wire  [31:0] st, dtv, sp, off, trip, lock;

  tb_svpwm_core u_tb (
    .rst_ni, .en_i, .mode_i(3'd0), .freq_i(24'sd107374), .theta_i(16'd0), .v1_i(16'sd0), .v2_i(16'sd0),
    .vf_boost_i(16'd0), .vf_slope_i(16'd0), .vf_mmax_i(16'd0), .dpwm_i(2'd0), .upd_i(2'd0), .presc_i(8'd0),
    .adc_trig_i(2'd0), .sync_en_i(1'b0), .sync_i(1'b0), .m_i(16'd29491), .period_i(16'd1536), .dt_i(10'd48),
    .mp_i(10'd0), .fault_i(1'b0), .fault_clear_i(1'b0), .trip_cbc_i(1'b0), .safe_lo_i(1'b0), .pol_i(2'd0),
    .lock_i(1'b0), .trace_i(1'b0), .clk,
    .mon(), .gate_hi_o(), .gate_lo_o(), .pole_o(), .carrier_o(), .carrier_up_o(), .valley_o(), .peak_o(),
    .sector_o(), .cmp_o(), .period_o(), .running_o(), .update_o(), .adc_trig_o(), .sync_o(), .sat_o(),
    .cfg_err_o(), .period_clamp_o(), .freq_clamp_o(), .fault_o(), .tripped_o(), .locked_o(),
    .shoot_through_count(st), .dead_time_violations(dtv), .short_pulse_count(sp), .off_violations(off),
    .trip_violations_o(trip), .lock_violations_o(lock)
  );

  initial begin
    if (!$value$plusargs("clocks=%d", clocks)) clocks = 64'd1_000_000;
    repeat (3) @(posedge clk);
    rst_ni = 1'b1;
    repeat (3) @(posedge clk);
    en_i = 1'b1;
    repeat (clocks) @(posedge clk);
    $display("tb_core_bench: %0d clocks, violations %0d %0d %0d %0d %0d %0d", clocks, st, dtv, sp, off, trip,
             lock);
    $finish;
  end
endmodule
`default_nettype wire
