// SPDX-License-Identifier: Apache-2.0
// svpwm_config: the configuration stage of svpwm_core -- the run register, the locked configuration
// (dead times, minimum pulse, trip mode, safe state, polarity), the period clamp and the period /
// dead-time pipeline: configuration (locked) -> use (one clock later) -> next (sampled before each valley)
// -> active (from the valley on), and whether that sample changes them (an update is then forced).
// Run: run_o is en_i of the clock before (the modulator starts one clock after en_i rises:
// fixed.START_DELAY), but not in the first svpwm_pkg::ArmClocks (4) clocks after reset, so that the
// configuration registers, the lowest legal period, the clamped period and the idle loads all happen
// before the carrier starts; with sync_en_i (feature SYNC), not before a sync_i pulse (another core's
// sync_o: the clock before its valley). upd_run_o is a twin of run_o (equal in every clock: formal) with
// its own feedback, so that synthesis keeps it: it drives the update logic's ~120 enables (one run net
// for all enables was the iCEBreaker's worst path at 48 MHz); in the tiny build it is run_o.
// Lock: lock_i sets locked_o until reset; until then dt_i, dtf_i / dtf_en_i, mp_i, trip_cbc_i and
// safe_lo_i are registered every clock, pol_i while not running.
// Dead times: the falling dead time (dtf_i when dtf_en_i, else dt_i) travels beside dt through every
// stage, so both change together at a valley, and so does "dtf > dt" (dtf_gt), which selects the larger
// one for the calculator's minimum-pulse threshold max(dt, dtf) + mp (a 10-bit compare in front of that
// adder would not meet 48 MHz on the UP5K). A build without DTF has one dead time: its dtf is dt at every
// stage (the dtf / dtf_gt flops are not read and not built).
// Period clamp: period_i below max(MinPeriod, 2 (max(dt, dtf) + mp)) is lengthened to it (period_clamp_o)
// -- the dead time is never shortened; the clamped period is registered (period_load_o while idle).
// Parameters: Features - the build (svpwm_pkg; DTF, SYNC and the tiny build are read here); CntWidth,
//             DtWidth, MinPeriod, GatePol as svpwm_core's.
// Latency: the configuration registers one clock after the ports, the use stage one more; next at a
//          valley sample (smp_valley_i) or while stopped; active at the valley (load_i) or while stopped;
//          chg_o compares the clamped period (one clock after period_i) and the use stage with the active
//          values, registered, valid at every sample point.
`default_nettype none

module svpwm_config #(
  parameter logic [31:0] Features  = svpwm_pkg::CfgFull,
  parameter int          CntWidth  = 16,
  parameter int          DtWidth   = 10,
  parameter int          MinPeriod = svpwm_pkg::min_period(Features),
  parameter logic [1:0]  GatePol   = 2'b00
) (
  input  logic                clk_i,           // core clock
  input  logic                rst_ni,          // asynchronous reset, active low
  input  logic                en_i,            // run request (svpwm_core's en_i)
  input  logic                sync_en_i,       // start only on a sync_i pulse (feature SYNC)
  input  logic                sync_i,          // another core's sync_o
  input  logic                lock_i,          // lock the configuration until reset
  input  logic [DtWidth-1:0]  dt_i,            // rising dead time
  input  logic [DtWidth-1:0]  dtf_i,           // falling dead time (feature DTF)
  input  logic                dtf_en_i,        // 1: use dtf_i (feature DTF)
  input  logic [DtWidth-1:0]  mp_i,            // minimum gate pulse
  input  logic                trip_cbc_i,      // trip mode: 0 latched, 1 cycle-by-cycle
  input  logic                safe_lo_i,       // safe state: 0 all off, 1 low sides on
  input  logic [1:0]          pol_i,           // {lo, hi} pin polarity
  input  logic [CntWidth-1:0] period_i,        // half carrier period request
  input  logic                smp_valley_i,    // the sample before a valley (svpwm_update)
  input  logic                load_i,          // the next clock is a valley (svpwm_carrier)
  input  logic [CntWidth-1:0] period_act_i,    // active half period (svpwm_carrier)
  output logic                run_o,           // the modulator runs (a register)
  output logic                run_next_o,      // run_o's next value
  output logic                upd_run_o,       // run_o's twin for the update logic
  output logic                locked_o,        // configuration locked
  output logic                cbc_o,           // trip mode, locked
  output logic                safe_lo_o,       // safe state, locked
  output logic [1:0]          pol_o,           // pin polarity, locked
  output logic [CntWidth-1:0] period_load_o,   // the carrier's next period (next, or the clamped port idle)
  output logic [CntWidth-1:0] period_next_o,   // period for the next valley
  output logic [DtWidth-1:0]  dt_next_o,       // dead times and minimum pulse for the next valley
  output logic [DtWidth-1:0]  dtf_next_o,
  output logic                dtf_gt_next_o,   // dtf_next_o > dt_next_o
  output logic [DtWidth-1:0]  mp_next_o,
  output logic [DtWidth-1:0]  dt_o,            // active rising dead time (the gates' from the next clock)
  output logic [DtWidth-1:0]  dtf_o,           // active falling dead time (= dt_o without DTF)
  output logic                dtf_gt_o,        // dtf_o > dt_o
  output logic [DtWidth-1:0]  mp_o,            // active minimum pulse
  output logic                chg_o,           // the period, a dead time or mp differs from the active one
  output logic                period_clamp_o   // period_i was lengthened at the last valley sample
);

  localparam bit HasDtf  = svpwm_pkg::has(Features, svpwm_pkg::FeatDtf);
  localparam bit HasSync = svpwm_pkg::has(Features, svpwm_pkg::FeatSync);

  // ---- run ---------------------------------------------------------------------------------------
  logic [svpwm_pkg::ArmClocks-2:0] armed_q;
  logic                            run_d, run_q, sync_en, upd_run;

  assign sync_en = HasSync ? sync_en_i : 1'b0;
  assign run_d   = en_i && armed_q[svpwm_pkg::ArmClocks-2] && (run_q || !sync_en || sync_i);

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      armed_q <= '0;
      run_q   <= 1'b0;
    end else begin
      armed_q <= {armed_q[svpwm_pkg::ArmClocks-3:0], 1'b1};
      run_q   <= run_d;
    end
  end

  if (!svpwm_pkg::is_tiny(Features)) begin : gen_upd_run
    logic upd_run_d, upd_run_q;

    assign upd_run_d = en_i && armed_q[svpwm_pkg::ArmClocks-2] && (upd_run_q || !sync_en || sync_i);

    always_ff @(posedge clk_i or negedge rst_ni) begin
      if (!rst_ni) upd_run_q <= 1'b0;
      else         upd_run_q <= upd_run_d;
    end

    assign upd_run = upd_run_q;
  end else begin : gen_one_run      // (the HX1K is full and fast enough)
    assign upd_run = run_q;
  end

  // ---- configuration registers, locked by lock_i until reset -------------------------------------
  logic               locked_q;
  logic [DtWidth-1:0] dt_cfg_q, dtf_cfg_q, mp_cfg_q;   // dtf_cfg_q: the falling dead time, dtf_en_i resolved
  logic [DtWidth-1:0] dt_max_cfg_q;                    // max(dt, dtf): registered beside them (timing)
  logic               dtf_gt_cfg_q;
  logic               cbc_q, safe_lo_q;
  logic [1:0]         pol_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      locked_q     <= 1'b0;
      dt_cfg_q     <= '0;
      dtf_cfg_q    <= '0;
      dt_max_cfg_q <= '0;
      dtf_gt_cfg_q <= 1'b0;
      mp_cfg_q     <= '0;
      cbc_q        <= 1'b0;
      safe_lo_q    <= 1'b0;
      pol_q        <= GatePol;
    end else begin
      if (lock_i) locked_q <= 1'b1;
      if (!locked_q) begin
        dt_cfg_q     <= dt_i;
        // (a build without DTF: dtf = dt from here on, in every stage; synthesis merges the copies)
        dtf_cfg_q    <= (HasDtf && dtf_en_i) ? dtf_i : dt_i;
        dt_max_cfg_q <= (HasDtf && dtf_en_i && dtf_i > dt_i) ? dtf_i : dt_i;
        dtf_gt_cfg_q <= HasDtf && dtf_en_i && dtf_i > dt_i;
        mp_cfg_q     <= mp_i;
        cbc_q        <= trip_cbc_i;
        safe_lo_q    <= safe_lo_i;
        if (!run_q) pol_q <= pol_i;
      end
    end
  end

  // ---- period clamp: the lowest legal period, registered (off the sampling paths); dt / mp are used
  // one clock later too (the use stage), so a period is always clamped for the dead time it is used with
  logic [DtWidth-1:0]  dt_max_cfg;
  logic [DtWidth:0]    thr;             // max(dt, dtf) + minimum pulse
  logic [CntWidth-1:0] period_low, period_low_q, period_clamped;
  logic                period_under;
  logic [DtWidth-1:0]  dt_use_q, dtf_use_q, mp_use_q;
  logic                dtf_gt_use_q;

  assign dt_max_cfg = HasDtf ? dt_max_cfg_q : dt_cfg_q;
  assign thr        = {1'b0, dt_max_cfg} + {1'b0, mp_cfg_q};
  assign period_low = (CntWidth'({thr, 1'b0}) > CntWidth'(MinPeriod)) ? CntWidth'({thr, 1'b0})
                                                                    : CntWidth'(MinPeriod);

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      period_low_q <= CntWidth'(MinPeriod);
      dt_use_q     <= '0;
      dtf_use_q    <= '0;
      dtf_gt_use_q <= 1'b0;
      mp_use_q     <= '0;
    end else begin
      period_low_q <= period_low;
      dt_use_q     <= dt_cfg_q;
      dtf_use_q    <= dtf_cfg_q;
      dtf_gt_use_q <= dtf_gt_cfg_q;
      mp_use_q     <= mp_cfg_q;
    end
  end

  assign period_under   = period_i < period_low_q;
  assign period_clamped = period_under ? period_low_q : period_i;

  // ---- the forced update: the clamped period is registered too (one clock after the port), and so is
  // the comparison that forces an update (valid in every clock but the one after a load, i.e. at every
  // sample point): the sample strobes then reach the ~150 register enables they drive straight from
  // flip-flops. One compare per field, kept, then their OR: 4 LUT levels for the 60 bits (ABC made 7 of
  // the flat expression on the UP5K, the core's slowest path after the calculator's).
  logic [DtWidth-1:0]  dt_q, dtf_q, mp_q, dtf_cfg, dtf_act;
  logic                dtf_gt_q;
  logic [CntWidth-1:0] period_clamped_q;
  logic                period_under_q, period_ne_pin_q, period_ne_low_q, dtmp_chg_q;
  (* keep *) logic     dt_ne, dtf_ne, mp_ne;

  assign dtf_cfg = HasDtf ? dtf_cfg_q : dt_q;        // one dead time: = dtf_act, so no compare (dtf_ne 0)
  assign dtf_act = HasDtf ? dtf_q : dt_q;
  assign dt_ne   = dt_cfg_q != dt_q;
  assign dtf_ne  = dtf_cfg != dtf_act;
  assign mp_ne   = mp_cfg_q != mp_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      period_clamped_q <= CntWidth'(MinPeriod);
      period_under_q   <= 1'b0;
      period_ne_pin_q  <= 1'b0;
      period_ne_low_q  <= 1'b0;
      dtmp_chg_q       <= 1'b0;
    end else begin
      period_clamped_q <= period_clamped;
      period_under_q   <= period_under;
      period_ne_pin_q  <= period_i != period_act_i;
      period_ne_low_q  <= period_low_q != period_act_i;
      dtmp_chg_q       <= dt_ne || dtf_ne || mp_ne;
    end
  end

  // == (period_clamped_q != period_act || dt_use_q != dt_q || dtf_use_q != dtf_act || mp_use_q != mp_q):
  // the compares are registered side by side (the period one for both sides of the clamp), the clamp's
  // choice after them
  assign chg_o = (period_under_q ? period_ne_low_q : period_ne_pin_q) || dtmp_chg_q;

  // ---- next (sampled before every valley, or while stopped) and active (from the valley on) -------
  logic [CntWidth-1:0] period_next_d, period_next_q;
  logic [DtWidth-1:0]  dt_next_d, dt_next_q, dtf_next_d, dtf_next_q, mp_next_d, mp_next_q;
  logic [DtWidth-1:0]  dt_d, dtf_d, mp_d;
  logic                dtf_gt_next_d, dtf_gt_next_q, dtf_gt_d, period_clamp_d, period_clamp_q;

  always_comb begin
    period_next_d  = period_next_q;
    dt_next_d      = dt_next_q;
    dtf_next_d     = dtf_next_q;
    dtf_gt_next_d  = dtf_gt_next_q;
    mp_next_d      = mp_next_q;
    period_clamp_d = period_clamp_q;
    dt_d           = dt_q;
    dtf_d          = dtf_q;
    dtf_gt_d       = dtf_gt_q;
    mp_d           = mp_q;
    if (!run_q || smp_valley_i) begin
      period_next_d  = period_clamped_q;
      dt_next_d      = dt_use_q;
      dtf_next_d     = dtf_use_q;
      dtf_gt_next_d  = dtf_gt_use_q;
      mp_next_d      = mp_use_q;
      period_clamp_d = period_under_q;
    end
    if (!upd_run) begin                   // idle: the dead time follows the configuration
      dt_d     = dt_use_q;
      dtf_d    = dtf_use_q;
      dtf_gt_d = dtf_gt_use_q;
      mp_d     = mp_use_q;
    end else if (load_i) begin            // valley: period (in the carrier), dead time, minimum pulse
      dt_d     = dt_next_q;
      dtf_d    = dtf_next_q;
      dtf_gt_d = dtf_gt_next_q;
      mp_d     = mp_next_q;
    end
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      period_next_q  <= CntWidth'(MinPeriod);
      dt_next_q      <= '0;
      dtf_next_q     <= '0;
      dtf_gt_next_q  <= 1'b0;
      mp_next_q      <= '0;
      period_clamp_q <= 1'b0;
      dt_q           <= '0;
      dtf_q          <= '0;
      dtf_gt_q       <= 1'b0;
      mp_q           <= '0;
    end else begin
      period_next_q  <= period_next_d;
      dt_next_q      <= dt_next_d;
      dtf_next_q     <= dtf_next_d;
      dtf_gt_next_q  <= dtf_gt_next_d;
      mp_next_q      <= mp_next_d;
      period_clamp_q <= period_clamp_d;
      dt_q           <= dt_d;
      dtf_q          <= dtf_d;
      dtf_gt_q       <= dtf_gt_d;
      mp_q           <= mp_d;
    end
  end

  // idle: the clamped port, registered (the carrier's period and period - 1 then start from flip-flops,
  // not from en_i, the period compare and its mux); the core idles >= 4 clocks after reset (armed_q)
  assign period_load_o  = run_q ? period_next_q : period_clamped_q;

  assign run_o          = run_q;
  assign run_next_o     = run_d;
  assign upd_run_o      = upd_run;
  assign locked_o       = locked_q;
  assign cbc_o          = cbc_q;
  assign safe_lo_o      = safe_lo_q;
  assign pol_o          = pol_q;
  assign period_next_o  = period_next_q;
  assign dt_next_o      = dt_next_q;
  assign dtf_next_o     = dtf_next_q;
  assign dtf_gt_next_o  = dtf_gt_next_q;
  assign mp_next_o      = mp_next_q;
  assign dt_o           = dt_q;
  assign dtf_o          = dtf_act;
  assign dtf_gt_o       = dtf_gt_q;
  assign mp_o           = mp_q;
  assign period_clamp_o = period_clamp_q;

`ifdef FORMAL
  // (proven in svpwm_core's formal/core.sby, with the core's reset assumption)
  logic f_past_valid = 1'b0;
  always_ff @(posedge clk_i) f_past_valid <= 1'b1;

  always_comb if (rst_ni) assert (upd_run == run_q);              // the twin run register
  always_comb if (rst_ni) assert (period_next_q >= CntWidth'(MinPeriod));
  // a locked configuration does not change
  always_ff @(posedge clk_i) if (f_past_valid && $past(rst_ni) && rst_ni && $past(locked_q))
    assert (locked_q && dt_cfg_q == $past(dt_cfg_q) && dtf_cfg_q == $past(dtf_cfg_q)
            && mp_cfg_q == $past(mp_cfg_q) && pol_q == $past(pol_q) && safe_lo_q == $past(safe_lo_q)
            && cbc_q == $past(cbc_q));
  // the registered max(dt, dtf) and "dtf > dt" flags are those of the dead times beside them
  if (HasDtf) begin : gen_f_dtf
    always_comb if (rst_ni) begin
      assert (dt_max_cfg_q == ((dt_cfg_q >= dtf_cfg_q) ? dt_cfg_q : dtf_cfg_q));
      assert (dtf_gt_cfg_q == (dtf_cfg_q > dt_cfg_q) && dtf_gt_use_q == (dtf_use_q > dt_use_q));
      assert (dtf_gt_next_q == (dtf_next_q > dt_next_q) && dtf_gt_q == (dtf_q > dt_q));
    end
  end
  always_comb cover (rst_ni && locked_q && dt_q != '0 && run_q);
`endif

endmodule

`default_nettype wire
