// SPDX-License-Identifier: Apache-2.0
// tb_svpwm_core: simulation harness around svpwm_core. Generates the clock (10 ns) in SystemVerilog
// (3x faster than a Python clock on Verilator), bundles the outputs cocotb watches by edges into one
// word, and checks the gate pins on every clock: never both gates of a leg on, dead time before every
// turn-on (across resets too), no on-pulse shorter than max(dead time, minimum pulse) unless cut by a
// disable/trip/reset, all gates off during reset and while disabled, no turn-on in the reset hold, the
// pins safe in every clock of a trip.
`timescale 1ns / 1ps
`default_nettype none

module tb_svpwm_core #(
  parameter logic [31:0] Features = svpwm_pkg::CfgFull,
  parameter int CntWidth   = 16,
  parameter int PhaseWidth = 34,
  parameter int FreqWidth  = 24,
  parameter int DtWidth    = 10,
  parameter int MinPeriod  = svpwm_pkg::min_period(Features),
  parameter logic [1:0] GatePol = 2'b00
) (
  input  logic                        rst_ni,
  input  logic                        en_i,
  input  logic [2:0]                  mode_i,
  input  logic signed [FreqWidth-1:0] freq_i,
  input  logic [15:0]                 theta_i,
  input  logic signed [15:0]          v1_i,
  input  logic signed [15:0]          v2_i,
  input  logic [15:0]                 vf_boost_i,
  input  logic [15:0]                 vf_slope_i,
  input  logic [15:0]                 vf_mmax_i,
  input  logic [1:0]                  dpwm_i,
  input  logic [1:0]                  upd_i,
  input  logic [7:0]                  presc_i,
  input  logic [1:0]                  adc_trig_i,
  input  logic [1:0]                  adc_pt_en_i,
  input  logic [1:0]                  adc_pt_dn_i,
  input  logic [2*CntWidth-1:0]       adc_pt_cnt_i,
  input  logic [CntWidth:0]           win_min_i,
  input  logic                        dtc_en_i,
  input  logic                        om_i,
  input  logic                        vsc_en_i,
  input  logic [2:0]                  isign_i,
  input  logic                        sync_en_i,
  input  logic                        sync_i,
  input  logic [15:0]                 m_i,
  input  logic [CntWidth-1:0]         period_i,
  input  logic [DtWidth-1:0]          dt_i,
  input  logic [DtWidth-1:0]          dtf_i,
  input  logic                        dtf_en_i,
  input  logic [DtWidth-1:0]          mp_i,
  input  logic                        fault_i,
  input  logic                        fault_clear_i,
  input  logic                        trip_cbc_i,
  input  logic                        safe_lo_i,
  input  logic [1:0]                  pol_i,
  input  logic                        lock_i,
  input  logic                        trace_i,      // record every clock (C lines, below) while high
  output logic                        clk,
  output logic [8:0]                  mon,          // {pole[2:0], gate_lo[2:0], gate_hi[2:0]}
  output logic [2:0]                  gate_hi_o,
  output logic [2:0]                  gate_lo_o,
  output logic [2:0]                  pole_o,
  output logic [CntWidth-1:0]         carrier_o,
  output logic                        carrier_up_o,
  output logic                        valley_o,
  output logic                        peak_o,
  output logic [2:0]                  sector_o,
  output logic [3*CntWidth-1:0]       cmp_o,
  output logic [CntWidth-1:0]         period_o,
  output logic                        running_o,
  output logic                        update_o,
  output logic                        adc_trig_o,
  output logic [1:0]                  adc_pt_o,
  output logic [3*(CntWidth+1)-1:0]   win_lo_o,
  output logic [3*(CntWidth+1)-1:0]   win_hi_o,
  output logic [2:0]                  win_ok_o,
  output logic [1:0]                  win_recon_o,
  output logic                        sync_o,
  output logic                        sat_o,
  output logic                        cfg_err_o,
  output logic                        period_clamp_o,
  output logic                        freq_clamp_o,
  output logic                        fault_o,
  output logic                        tripped_o,
  output logic                        locked_o,
  output logic [31:0]                 shoot_through_count,   // see the checker below
  output logic [31:0]                 dead_time_violations,
  output logic [31:0]                 short_pulse_count,
  output logic [31:0]                 off_violations,
  output logic [31:0]                 trip_violations_o,
  output logic [31:0]                 lock_violations_o,
  output logic [31:0]                 reset_dt_violations_o,    // (below: the checks across a reset
  output logic [31:0]                 reset_hold_violations_o,  //  and the trip gap)
  output logic [31:0]                 trip_gap_violations_o
);

  initial clk = 1'b0;
  always #5 clk = ~clk;

  svpwm_core #(
    .Features   (Features),
    .CntWidth   (CntWidth),
    .PhaseWidth (PhaseWidth),
    .FreqWidth  (FreqWidth),
    .DtWidth    (DtWidth),
    .MinPeriod  (MinPeriod),
    .GatePol    (GatePol)
  ) u_core (
    .clk_i          (clk),
    .rst_ni         (rst_ni),
    .en_i           (en_i),
    .mode_i         (mode_i),
    .freq_i         (freq_i),
    .theta_i        (theta_i),
    .v1_i           (v1_i),
    .v2_i           (v2_i),
    .vf_boost_i     (vf_boost_i),
    .vf_slope_i     (vf_slope_i),
    .vf_mmax_i      (vf_mmax_i),
    .dpwm_i         (dpwm_i),
    .upd_i          (upd_i),
    .presc_i        (presc_i),
    .adc_trig_i     (adc_trig_i),
    .adc_pt_en_i    (adc_pt_en_i),
    .adc_pt_dn_i    (adc_pt_dn_i),
    .adc_pt_cnt_i   (adc_pt_cnt_i),
    .win_min_i      (win_min_i),
    .dtc_en_i       (dtc_en_i),
    .om_i           (om_i),
    .vsc_en_i       (vsc_en_i),
    .isign_i        (isign_i),
    .sync_en_i      (sync_en_i),
    .sync_i         (sync_i),
    .m_i            (m_i),
    .period_i       (period_i),
    .dt_i           (dt_i),
    .dtf_i          (dtf_i),
    .dtf_en_i       (dtf_en_i),
    .mp_i           (mp_i),
    .fault_i        (fault_i),
    .fault_clear_i  (fault_clear_i),
    .trip_cbc_i     (trip_cbc_i),
    .safe_lo_i      (safe_lo_i),
    .pol_i          (pol_i),
    .lock_i         (lock_i),
    .gate_hi_o      (gate_hi_pin),
    .gate_lo_o      (gate_lo_pin),
    .pole_o         (pole_o),
    .carrier_o      (carrier_o),
    .carrier_up_o   (carrier_up_o),
    .valley_o       (valley_o),
    .peak_o         (peak_o),
    .sector_o       (sector_o),
    .cmp_o          (cmp_o),
    .period_o       (period_o),
    .running_o      (running_o),
    .update_o       (update_o),
    .adc_trig_o     (adc_trig_o),
    .adc_pt_o       (adc_pt_o),
    .win_lo_o       (win_lo_o),
    .win_hi_o       (win_hi_o),
    .win_ok_o       (win_ok_o),
    .win_recon_o    (win_recon_o),
    .sync_o         (sync_o),
    .sat_o          (sat_o),
    .cfg_err_o      (cfg_err_o),
    .period_clamp_o (period_clamp_o),
    .freq_clamp_o   (freq_clamp_o),
    .fault_o        (fault_o),
    .tripped_o      (tripped_o),
    .locked_o       (locked_o)
  );

  // pins -> gate on/off (undo the polarity in force, so the checks below speak of switches)
  logic [2:0] gate_hi_pin, gate_lo_pin;
  assign gate_hi_o = u_core.pol[0] ? ~gate_hi_pin : gate_hi_pin;
  assign gate_lo_o = u_core.pol[1] ? ~gate_lo_pin : gate_lo_pin;

  assign mon = {pole_o, gate_lo_o, gate_hi_o};

  // ---- event recorder for svpwm_tb.CoreTB (Python then wakes only where an input changes) ---------
  // With +svpwm_rec=<file>, writes to <file> (times in ns, values in hex), each line flushed:
  //   M t mon                                   every change of mon (the last one of a time step last)
  //   V t cmp sector period running sat         each rising edge of valley_o, values 1 ns after it
  //   P t cmp running                           each rising edge of peak_o, likewise
  //   U t                                       each rising edge of update_o, likewise
  //   A t pts carrier up                        each clock with an ADC trigger point (adc_pt_o), likewise
  //                                             (written at the next rising edge, with t of this one + 1)
  //   W t lo hi ok recon                        9 clocks after each valley and peak: the shunt-window report
  //   C t valley peak period adc carrier tripped fault hi lo pclamp carry  each rising clock edge while
  //                                             trace_i is high (hi / lo: the gates as gate_hi_o / gate_lo_o;
  //                                             carry: the core's volt-second carry register car_q),
  //                                             likewise
  //                                             (for short per-clock checks without a Python wake per clock)
  // 1 ns after a rising clock edge every output has settled (what cocotb reads in ReadOnly after the
  // edge) and nothing else happens until the falling edge, where cocotb writes the inputs.
  integer rec_fd = 0;
  string  rec_path;
  initial if ($value$plusargs("svpwm_rec=%s", rec_path)) begin
    rec_fd = $fopen(rec_path, "w");
    if (rec_fd == 0) $fatal(1, "tb_svpwm_core: cannot open %s", rec_path);
  end
  always @(mon) if (rec_fd != 0) begin
    $fwrite(rec_fd, "M %0d %0h\n", $time, mon);
    $fflush(rec_fd);
  end
  always @(posedge valley_o) if (rec_fd != 0) begin
    #1;
    $fwrite(rec_fd, "V %0d %0h %0h %0h %0h %0h\n", $time, cmp_o, sector_o, period_o, running_o, sat_o);
    $fflush(rec_fd);
  end
  always @(posedge peak_o) if (rec_fd != 0) begin
    #1;
    $fwrite(rec_fd, "P %0d %0h %0h\n", $time, cmp_o, running_o);
    $fflush(rec_fd);
  end
  // (a point may fire in two clocks in a row, the last clock of a period and the next valley: the pulse is
  // registered with a count, which changes once per clock with a pulse, and written at that change, with
  // the time of the clock it came from)
  integer                rec_a_n = 0;
  logic [1:0]            rec_a_pt;
  logic [CntWidth-1:0]   rec_a_car;
  logic                  rec_a_up;
  always @(posedge clk) if (adc_pt_o != 2'b00) begin
    rec_a_n   <= rec_a_n + 1;
    rec_a_pt  <= adc_pt_o;
    rec_a_car <= carrier_o;
    rec_a_up  <= carrier_up_o;
  end
  always @(rec_a_n) if (rec_fd != 0 && rec_a_n != 0) begin
    $fwrite(rec_fd, "A %0d %0h %0h %0h\n", $time - 9, rec_a_pt, rec_a_car, rec_a_up);
    $fflush(rec_fd);
  end
  always @(posedge valley_o or posedge peak_o) if (rec_fd != 0) begin
    repeat (9) @(posedge clk);
    #1;
    $fwrite(rec_fd, "W %0d %0h %0h %0h %0h\n", $time, win_lo_o, win_hi_o, win_ok_o, win_recon_o);
    $fflush(rec_fd);
  end
  always @(posedge update_o) if (rec_fd != 0) begin
    #1;
    $fwrite(rec_fd, "U %0d\n", $time);
    $fflush(rec_fd);
  end
  always @(posedge clk) if (rec_fd != 0 && trace_i === 1'b1) begin
    #1;
    $fwrite(rec_fd, "C %0d %0h %0h %0h %0h %0h %0h %0h %0h %0h %0h %0h\n", $time, valley_o, peak_o, period_o,
            adc_trig_o, carrier_o, tripped_o, fault_o, gate_hi_o, gate_lo_o, period_clamp_o,
            u_core.calc_carry_in);
    $fflush(rec_fd);
  end
  assign trip_violations_o       = trip_violations;
  assign lock_violations_o       = lock_violations;
  assign reset_dt_violations_o   = reset_dt_violations;
  assign reset_hold_violations_o = reset_hold_violations;
  assign trip_gap_violations_o   = trip_gap_violations;

  // ---- per-clock safety checker on the pins (polarity undone) ------------------------------------
  // Uses the dead times and minimum pulse the core has in force (u_core.dt_act / dtf_act / mp_act, themselves
  // checked against the model by the bit-exact tests) and the configuration registers for the lock check.
  //   shoot_through_count:  clocks with both gates of a leg on
  //   dead_time_violations: a high side turned on less than dt (a low side: dtf) after the other gate of
  //                         its leg turned off
  //   short_pulse_count:    an on-pulse shorter than max(dt, dtf, mp), not started or cut by a forced state
  //                         (reset, a reset pulse between two clock edges included, en_i low, trip)
  //   off_violations:       a gate on during reset; a gate on while disabled and not tripped
  //   trip_violations:      fault_i high (or the trip latched) and a high side on, or a low side on
  //                         while the safe state is "all off"
  //   lock_violations:      a locked configuration register changed
  //   reset_dt_violations:  a leg's first turn-on after a reset less than the dead time in force before the
  //                         reset (dt for a high side, dtf for a low side; the largest of every reset since
  //                         the leg last turned on) after the other gate turned off. A gate the reset turned
  //                         off (a reset pulse between two clock edges included) counts as off from the first
  //                         edge after it (the conservative end of that clock). The core clears its dead-time
  //                         registers with the reset: this uses the checker's own copy (checker state is never
  //                         reset). Counted in dead_time_violations as well.
  //   reset_hold_violations: a gate turned on at a clock edge less than CntMax + 1 = 2^DtWidth edges after a
  //                         reset release (edge 1: the first rising edge after it; rtl/deadtime.sv's reset
  //                         hold: the first turn-on is at edge CntMax + 1 at the earliest)
  //   trip_gap_violations:  a pin not safe (a high side on; a low side on unless safe_lo) in a clock of a trip:
  //                         from the first clock edge that sees the fault (fault_i high at it) as long as
  //                         svpwm_gate_out's synchroniser or latch holds it, i.e. until the release (the pins
  //                         sampled at each rising edge, before it); a glitch that no edge sees is not a trip
  // Cost: the loop over the legs runs only in a clock where a gate turns on or off (a few per carrier
  // period); on-pulse lengths come from the turn-on clock, not from per-clock counters (Icarus runs the
  // whole core ~1.6x faster than with the per-clock loop).
  logic [DtWidth-1:0] dt_dec, dtf_dec, mp_dec;   // in force during the previous clock (the deciding clock)
  logic [2:0]         hi_prev, lo_prev, tainted;
  logic               en_prev, trip_prev, forced_prev;
  longint unsigned    cyc, last_off [6];    // clock counter; last turn-off of each gate (hi 0..2, lo 3..5)
  longint unsigned    last_on [6];          // last turn-on of each gate
  logic               forced;
  logic [3*DtWidth+3:0] lk_cfg, cfg;        // the lockable configuration: at the first locked clock, now
  logic               lk_valid;
  logic [31:0]        trip_violations, lock_violations;
  logic [2:0]         rise_hi, rise_lo, fall_hi, fall_lo;

  // a reset pulse between two clock edges (asynchronous: no edge sees rst_ni low) forces like a sampled one
  int unsigned        rst_falls = 0, rst_falls_seen = 0;
  // the dead times in force as a reset comes (the core clears its registers with it): the checker's dt_dec
  // (in force in this clock) and, to be safe, the core's registers at the last falling clock edge out of reset
  // (those of the next clock, unless the reset came before that edge); the largest over the resets no
  // rising clock edge has seen yet
  localparam logic [63:0] CntMax = (64'd1 << DtWidth) - 1;
  logic [DtWidth-1:0] dt_live = '0, dtf_live = '0, rst_dt = '0, rst_dtf = '0;
  always @(negedge clk) if (rst_ni === 1'b1) begin
    dt_live  <= u_core.dt_act;
    dtf_live <= u_core.dtf_act;
  end
  always @(negedge rst_ni) begin
    if (rst_falls == rst_falls_seen) begin       // the edges saw the last one: start again
      rst_dt  = '0;
      rst_dtf = '0;
    end
    if (dt_live  > rst_dt)  rst_dt  = dt_live;
    if (dt_dec   > rst_dt)  rst_dt  = dt_dec;
    if (dtf_live > rst_dtf) rst_dtf = dtf_live;
    if (dtf_dec  > rst_dtf) rst_dtf = dtf_dec;
    rst_falls = rst_falls + 1;
  end
  // the reset's requirements, per leg until its first turn-on after the reset: the high side's, the low side's
  logic [DtWidth-1:0] rq_hi [3], rq_lo [3];
  logic [2:0]         rst_pend = '0;
  logic               rst_prev = 1'b0, rst_evt, trip_chk;
  longint unsigned    rel_cyc = 0;           // cyc at the first rising edge after the last reset release
  logic [31:0]        reset_dt_violations = 0, reset_hold_violations = 0, trip_gap_violations = 0;

  assign forced  = !rst_ni || rst_falls != rst_falls_seen || !en_i || tripped_o;
  assign rise_hi = gate_hi_o & ~hi_prev;
  assign rise_lo = gate_lo_o & ~lo_prev;
  assign fall_hi = hi_prev & ~gate_hi_o;
  assign fall_lo = lo_prev & ~gate_lo_o;
  assign cfg     = {u_core.u_config.dt_cfg_q, u_core.u_config.dtf_cfg_q, u_core.u_config.mp_cfg_q, u_core.pol,
                    u_core.safe_lo, u_core.cbc};

  initial begin
    shoot_through_count  = 0;
    dead_time_violations = 0;
    short_pulse_count    = 0;
    off_violations       = 0;
    trip_violations      = 0;
    lock_violations      = 0;
    hi_prev              = '0;
    lo_prev              = '0;
    tainted              = '1;
    en_prev              = 1'b0;
    trip_prev            = 1'b0;
    forced_prev          = 1'b1;
    lk_valid             = 1'b0;
    cyc                  = 64'd1 << 40;
    for (int i = 0; i < 6; i++) begin
      last_off[i] = 0;
      last_on[i]  = 0;
    end
    for (int i = 0; i < 3; i++) begin
      rq_hi[i] = '0;
      rq_lo[i] = '0;
    end
  end

  // a reset since the last edge or now; the trip as the checker sees it at this edge
  assign rst_evt  = !rst_ni || rst_falls != rst_falls_seen;
  assign trip_chk = fault_i || u_core.u_gate_out.sync_q != '0 || u_core.u_gate_out.latch_q;

  // Each counter counts clocks (at most one per clock, whichever legs violate in it).
  always @(posedge clk) begin
    cyc     <= cyc + 1;
    rst_falls_seen <= rst_falls;
    dt_dec  <= u_core.dt_act;
    dtf_dec <= u_core.dtf_act;
    mp_dec  <= u_core.mp_act;
    hi_prev <= gate_hi_o;
    lo_prev <= gate_lo_o;
    en_prev <= en_i;
    if (!rst_ni && (gate_hi_o != '0 || gate_lo_o != '0)) off_violations <= off_violations + 1;
    trip_prev   <= u_core.trip_sync;
    forced_prev <= forced;
    if (rst_ni && !en_i && !en_prev && !tripped_o && !u_core.trip_sync && !trip_prev
        && (gate_hi_o != '0 || gate_lo_o != '0))
      off_violations <= off_violations + 1;
    if ((fault_i || u_core.u_gate_out.latch_q) && gate_hi_o != '0) trip_violations <= trip_violations + 1;
    if ((fault_i || u_core.u_gate_out.latch_q) && !u_core.safe_lo && gate_lo_o != '0)
      trip_violations <= trip_violations + 1;
    // lock: capture at the first locked clock, then nothing may change until reset
    if (rst_evt) lk_valid <= 1'b0;         // (a reset pulse between two clock edges unlocks too)
    else if (u_core.locked && !lk_valid) begin
      lk_valid <= 1'b1;
      lk_cfg   <= cfg;
    end else if (lk_valid && lk_cfg != cfg)
      lock_violations <= lock_violations + 1;
    if ((gate_hi_o & gate_lo_o) != '0) shoot_through_count <= shoot_through_count + 1;
    // the trip gap: the pins safe in every clock the trip holds
    if (trip_chk && (gate_hi_o != '0 || (!u_core.safe_lo && gate_lo_o != '0))) begin
      trip_gap_violations <= trip_gap_violations + 1;
      $display("%t tb_svpwm_core: tripped, gates hi %b lo %b (safe_lo %b)", $time, gate_hi_o, gate_lo_o,
               u_core.safe_lo);
    end
    rst_prev <= rst_ni;
    if (rst_ni && (rst_falls != rst_falls_seen || !rst_prev)) rel_cyc <= cyc;   // edge 1 after a release
    if (forced) tainted <= '1;
    if ((rise_hi | rise_lo | fall_hi | fall_lo) != '0) begin
      for (int i = 0; i < 3; i++) begin
        // turn-on of the high side: the low side turned off at least dt clocks ago (dt in force when
        // deciding); a direct swap (other gate on the clock before) needs dt = 0; the low side: dtf
        if (rise_hi[i] && dt_dec != '0 && (lo_prev[i] || cyc - last_off[i+3] < 64'(dt_dec))) begin
          dead_time_violations <= dead_time_violations + 1;
          $display("%t tb_svpwm_core: leg %0d high side on %0d clocks after the low side off, dt %0d",
                   $time, i, cyc - last_off[i+3], dt_dec);
        end
        if (rise_lo[i] && dtf_dec != '0 && (hi_prev[i] || cyc - last_off[i] < 64'(dtf_dec))) begin
          dead_time_violations <= dead_time_violations + 1;
          $display("%t tb_svpwm_core: leg %0d low side on %0d clocks after the high side off, dtf %0d",
                   $time, i, cyc - last_off[i], dtf_dec);
        end
        // the first turn-on after a reset: the dead time in force before it as well
        if (rise_hi[i] && rst_pend[i] && rq_hi[i] != '0 && (lo_prev[i] || cyc - last_off[i+3] < 64'(rq_hi[i]))) begin
          dead_time_violations <= dead_time_violations + 1;
          reset_dt_violations  <= reset_dt_violations + 1;
          $display("%t tb_svpwm_core: leg %0d high side on %0d clocks after the low side off, dt %0d before a reset",
                   $time, i, cyc - last_off[i+3], rq_hi[i]);
        end
        if (rise_lo[i] && rst_pend[i] && rq_lo[i] != '0 && (hi_prev[i] || cyc - last_off[i] < 64'(rq_lo[i]))) begin
          dead_time_violations <= dead_time_violations + 1;
          reset_dt_violations  <= reset_dt_violations + 1;
          $display("%t tb_svpwm_core: leg %0d low side on %0d clocks after the high side off, dtf %0d before a reset",
                   $time, i, cyc - last_off[i], rq_lo[i]);
        end
        // the reset hold: a turn-on at edge k after the release is seen here at edge k + 1, cyc = rel_cyc + k
        if ((rise_hi[i] || rise_lo[i]) && cyc - rel_cyc < CntMax + 1) begin
          reset_hold_violations <= reset_hold_violations + 1;
          $display("%t tb_svpwm_core: leg %0d gate on at edge %0d after a reset release (< %0d)", $time, i,
                   cyc - rel_cyc, CntMax + 1);
        end
        if (rise_hi[i] || rise_lo[i]) rst_pend[i] <= 1'b0;
        // (a gate the reset turned off went off between the last edge and this one: counted as off from
        // this edge on, the conservative end)
        if (fall_hi[i]) last_off[i]   <= rst_evt ? cyc + 1 : cyc;
        if (fall_lo[i]) last_off[i+3] <= rst_evt ? cyc + 1 : cyc;
        if (rise_hi[i]) last_on[i]    <= cyc;
        if (rise_lo[i]) last_on[i+3]  <= cyc;
        // on-pulse length (clocks from the turn-on to the turn-off): a pulse is exempt if a forced state
        // started it, cut it or happened in it
        if (((fall_hi[i] && (cyc - last_on[i] < 64'(dt_dec) || cyc - last_on[i] < 64'(dtf_dec)
                             || cyc - last_on[i] < 64'(mp_dec)))
             || (fall_lo[i] && (cyc - last_on[i+3] < 64'(dt_dec) || cyc - last_on[i+3] < 64'(dtf_dec)
                                || cyc - last_on[i+3] < 64'(mp_dec))))
            && !forced && !tainted[i])
          short_pulse_count <= short_pulse_count + 1;
        if (!forced && !forced_prev && (rise_hi[i] || rise_lo[i]))
          tainted[i] <= 1'b0;              // a clean turn-on starts an unforced pulse
      end
    end
    if (rst_evt) begin                     // a reset: each leg owes the dead times in force before it
      for (int i = 0; i < 3; i++) begin
        rq_hi[i] <= (rst_pend[i] && rq_hi[i] > rst_dt) ? rq_hi[i] : rst_dt;
        rq_lo[i] <= (rst_pend[i] && rq_lo[i] > rst_dtf) ? rq_lo[i] : rst_dtf;
      end
      rst_pend <= '1;
    end
  end

endmodule

`default_nettype wire
