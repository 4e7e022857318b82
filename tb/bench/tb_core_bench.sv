// SPDX-License-Identifier: Apache-2.0
// tb_core_bench: raw simulation throughput of the full core in the regression harness (tb_svpwm_core:
// SV clock, the per-clock pin checker, the event record), without cocotb: constant inputs, frequency word,
// m, period and dead time from plusargs (scripts/bench.py: RAW_INPUTS, Minas Fig. 10: 50 Hz, m = 0.9,
// P = 1536, 1 us dead time at 48 MHz), the others 0. The reset and enable sequence is CoreTB's
// (svpwm_tb.py): reset for 3 clocks, released after a rising edge, en_i set after the rising edge
// svpwm_pkg::ArmClocks + 2 clocks later (here half a clock after those edges, which the clocked logic
// sees the same way as cocotb's writes right after the rising edge, without a race); then +clocks=<n>
// clocks, the enable time and the checker's counters on stdout. With
// +svpwm_rec=<file> the harness records every edge, so scripts/bench.py compares the run with the golden
// model (svpwm_tb.parse_record, the model started the same way). scripts/bench.py builds it with both
// simulators (Verilator --binary, Icarus) and times the run (`make bench`).
`timescale 1ns / 1ps
`default_nettype none
module tb_core_bench;
  logic        rst_ni = 1'b0, en_i = 1'b0;
  logic        clk;
  longint unsigned clocks = 64'd1_000_000;
  wire  [31:0] st, dtv, sp, off, trip, lock;
  int          freq, m, period, dt;     // +freq= +m= +period= +dt= (scripts/bench.py: RAW_INPUTS)

  tb_svpwm_core u_tb (
    .rst_ni, .en_i, .mode_i(3'd0), .freq_i(24'(freq)), .theta_i(16'd0), .v1_i(16'sd0), .v2_i(16'sd0),
    .vf_boost_i(16'd0), .vf_slope_i(16'd0), .vf_mmax_i(16'd0), .dpwm_i(2'd0), .upd_i(2'd0), .presc_i(8'd0),
    .adc_pt_en_i (2'b00), .adc_pt_dn_i (2'b00), .adc_pt_cnt_i ('0), .win_min_i ('0),
    .adc_trig_i(2'd0), .om_i(1'b0), .vsc_en_i(1'b0), .dtc_en_i(1'b0), .isign_i(3'd0), .sync_en_i(1'b0),
    .sync_i(1'b0), .m_i(16'(m)), .period_i(16'(period)), .dt_i(10'(dt)),
    .dtf_i(10'd0), .dtf_en_i(1'b0), .mp_i(10'd0), .fault_i(1'b0), .fault_clear_i(1'b0), .trip_cbc_i(1'b0), .safe_lo_i(1'b0), .pol_i(2'd0),
    .lock_i(1'b0), .trace_i(1'b0), .clk,
    .mon(), .gate_hi_o(), .gate_lo_o(), .pole_o(), .carrier_o(), .carrier_up_o(), .valley_o(), .peak_o(),
    .adc_pt_o (), .win_lo_o (), .win_hi_o (), .win_ok_o (), .win_recon_o (),
    .sector_o(), .cmp_o(), .period_o(), .running_o(), .update_o(), .adc_trig_o(), .sync_o(), .sat_o(),
    .cfg_err_o(), .period_clamp_o(), .freq_clamp_o(), .fault_o(), .tripped_o(), .locked_o(),
    .shoot_through_count(st), .dead_time_violations(dtv), .short_pulse_count(sp), .off_violations(off),
    .trip_violations_o(trip), .lock_violations_o(lock)
  );

  initial begin
    if (!$value$plusargs("clocks=%d", clocks)) clocks = 64'd1_000_000;
    if (!$value$plusargs("freq=%d", freq) || !$value$plusargs("m=%d", m) || !$value$plusargs("period=%d", period)
        || !$value$plusargs("dt=%d", dt))
      $fatal(1, "tb_core_bench: +freq=, +m=, +period= and +dt= are required (scripts/bench.py passes them)");
    repeat (3) @(posedge clk);
    #5 rst_ni = 1'b1;                   // half a clock after the edge: no race with the clocked processes
    repeat (svpwm_pkg::ArmClocks + 2) @(posedge clk);
    #5 en_i = 1'b1;                     // the core first samples it at the next rising edge
    $display("tb_core_bench: enable at %0d ns", $time - 5);   // the rising edge CoreTB would write it at
    repeat (clocks) @(posedge clk);    // (measured: faster on Verilator than one long delay)
    $display("tb_core_bench: %0d clocks, violations %0d %0d %0d %0d %0d %0d", clocks, st, dtv, sp, off, trip,
             lock);
    $finish;
  end
endmodule
`default_nettype wire
