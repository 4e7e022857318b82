// SPDX-License-Identifier: Apache-2.0
// svpwm_update: the update scheduler and the shadow / active registers of svpwm_core. It decides when
// the reference is sampled and a computation starts, gives the calculator the period, threshold and
// compensation amounts of the update it computes, and makes the result active at the update point.
// Sample points: SampleLead clocks before each valley (count == SampleLead counting down) and each peak
// (count == P - SampleLead counting up); the inputs are taken in the clock before (sample_o), from
// registered compares one clock earlier still (count == SampleLead + 2 / P - SampleLead - 2). Which
// opportunities update: upd_i (0 valley, 1 peak, 2 both; 3 is a valley update and err_o) and the
// prescaler (every presc_i + 1 opportunities), both taken before each valley or while stopped; a changed
// period, dead time or minimum pulse (chg_i) forces an update at that valley.
// Calculator operands (registered at its start, valid from its step 1): a valley update is computed for
// the period it starts and the dead times it comes with (the next registers), a peak update for the
// active ones: the period, thr = max(dt, dtf) + mp (the larger one by the registered flag: one mux level
// before the adder), the compensation amounts ceil(dt / 2) (hdr: a positive current loses it) and
// ceil(dtf / 2) (hdf: a negative one gains it) when dead-time compensation is on (fixed.dtc_amounts).
// Shadow / active: the results are taken at a load strobe (the clock before a valley or a peak) exactly
// when the computation of an update finishes (SampleLead is the pipeline length): compare values,
// sector, sat, err, valid, and the update pulse. The volt-second carry (fixed.snap_carry): per phase what
// the minimum-pulse rule dropped or widened at the last update (for its period), given to the next
// computation for the same period; cleared while stopped or tripped, and not given across a period change.
// Parameters: Features - the build (UPD, PRESC read here; SampleLead = svpwm_pkg::sample_lead(Features));
//             CntWidth, DtWidth, MinPeriod as svpwm_core's.
// Latency: calc_start_o the clock after sample_o; the active registers the clock after take_o;
//          calc_carry_o three clocks after take_o (the calculator's carry_o, valid two clocks after its
//          done_o, is registered then).
`default_nettype none

module svpwm_update #(
  parameter logic [31:0] Features  = svpwm_pkg::CfgFull,
  parameter int          CntWidth  = 16,
  parameter int          DtWidth   = 10,
  parameter int          MinPeriod = svpwm_pkg::min_period(Features)
) (
  input  logic                    clk_i,            // core clock
  input  logic                    rst_ni,           // asynchronous reset, active low
  input  logic                    en_i,             // svpwm_core's en_i (running_o)
  input  logic                    run_i,            // the modulator runs (svpwm_config)
  input  logic                    upd_run_i,        // its twin for the update logic
  input  logic [1:0]              upd_i,            // update at 0 valley 1 peak 2 both (feature UPD)
  input  logic [7:0]              presc_i,          // prescaler (feature PRESC)
  input  logic [CntWidth-1:0]     count_i,          // carrier (svpwm_carrier)
  input  logic                    up_i,
  input  logic                    load_i,
  input  logic                    point_i,          // running, the next clock is a valley or a peak
  input  logic [CntWidth-1:0]     period_load_i,    // the period the carrier loads (svpwm_config)
  input  logic                    chg_i,            // period / dead time / mp changes (svpwm_config)
  input  logic [CntWidth-1:0]     period_next_i,    // for the next valley (svpwm_config)
  input  logic [DtWidth-1:0]      dt_next_i,
  input  logic [DtWidth-1:0]      dtf_next_i,
  input  logic                    dtf_gt_next_i,
  input  logic [DtWidth-1:0]      mp_next_i,
  input  logic [CntWidth-1:0]     period_act_i,     // active (svpwm_carrier, svpwm_config)
  input  logic [DtWidth-1:0]      dt_i,
  input  logic [DtWidth-1:0]      dtf_i,
  input  logic                    dtf_gt_i,
  input  logic [DtWidth-1:0]      mp_i,
  input  logic                    dtc_i,            // the sampled reference's compensation on
  input  logic                    vsc_i,            // the sampled reference's carry on
  input  logic                    trip_i,           // tripped (svpwm_gate_out): no carry
  input  logic                    calc_done_i,      // the calculator's results (svpwm_calc)
  input  logic [3*CntWidth-1:0]   calc_cmp_i,
  input  logic [2:0]              calc_sector_i,
  input  logic                    calc_sat_i,
  input  logic                    calc_err_i,
  input  logic [3*DtWidth+5:0]    calc_carry_i,
  output logic                    sample_o,         // take the reference now
  output logic                    smp_valley_o,     // the sample clock before a valley
  output logic                    calc_start_o,     // start the calculator
  output logic [CntWidth-1:0]     calc_period_o,    // its operands
  output logic [DtWidth:0]        calc_thr_o,
  output logic [DtWidth-1:0]      calc_hdr_o,
  output logic [DtWidth-1:0]      calc_hdf_o,
  output logic [3*DtWidth+5:0]    calc_carry_o,
  output logic                    calc_carry_en_o,
  output logic                    take_o,           // the results become active in the next clock
  output logic [3*CntWidth-1:0]   cmp_o,            // active compare values
  output logic [2:0]              sector_o,         // their sector
  output logic                    valid_o,          // active values valid
  output logic                    running_o,        // en_i, running, valid
  output logic                    sat_o,            // the active values' reference was clamped
  output logic                    err_o,            // invalid mode (active values) or upd_i code
  output logic                    update_o          // pulse: new values active from this clock
);

`ifdef SVPWM_FORMAL_SHORT_LEAD
  localparam int SampleLead = 2;                    // formal/core.sby's cover tasks only (svpwm_core)
`else
  localparam int SampleLead = svpwm_pkg::sample_lead(Features);       // calculator + load 1
`endif
  localparam bit HasUpd   = svpwm_pkg::has(Features, svpwm_pkg::FeatUpd);
  localparam bit HasPresc = svpwm_pkg::has(Features, svpwm_pkg::FeatPresc);
  localparam bit HasDtf   = svpwm_pkg::has(Features, svpwm_pkg::FeatDtf);
  localparam int EW = DtWidth + 2;                  // carry width per phase

  // ---- sample points ----------------------------------------------------------------------------
  logic [CntWidth-1:0] peak_cnt_d, peak_cnt_q;      // P - SampleLead - 2 of the active period
  logic                smp_valley_d, smp_valley_q, smp_peak_d, smp_peak_q, smp_valley, smp_peak;

  assign peak_cnt_d   = load_i ? period_load_i - CntWidth'(SampleLead + 2) : peak_cnt_q;
  assign smp_valley_d = run_i && !up_i && count_i == CntWidth'(SampleLead + 2);
  assign smp_peak_d   = run_i && up_i && count_i == peak_cnt_q;
  assign smp_valley   = run_i && smp_valley_q;
  assign smp_peak     = run_i && smp_peak_q;

  // ---- which opportunities update (upd, prescaler), forced updates ------------------------------
  localparam logic [1:0] UpdPeak = 2'd1, UpdBoth = 2'd2;   // 2'd0: valley

  logic [1:0] upd_in;
  logic [7:0] presc_in;
  logic       upd_valley_d, upd_valley_q, upd_peak_d, upd_peak_q;   // the opportunities used
  logic       presc_zero_d, presc_zero_q;       // presc_cnt_d == 0, registered (this one updates)
  logic       upd_err_d, upd_err_q;
  logic [7:0] presc_d, presc_q, presc_cnt_d, presc_cnt_q;
  logic       opp_valley, opp_peak, forced, sample;

  assign upd_in     = HasUpd ? upd_i : 2'd0;
  assign presc_in   = HasPresc ? presc_i : 8'd0;
  assign opp_valley = smp_valley && upd_valley_q;
  assign opp_peak   = smp_peak && upd_peak_q;
  assign forced     = smp_valley && chg_i;
  assign sample     = ((opp_valley || opp_peak) && presc_zero_q) || forced;

  always_comb begin
    upd_valley_d = upd_valley_q;
    upd_peak_d   = upd_peak_q;
    upd_err_d    = upd_err_q;
    presc_d      = presc_q;
    presc_cnt_d  = presc_cnt_q;
    presc_zero_d = presc_zero_q;
    if (opp_valley || opp_peak) begin
      presc_cnt_d  = (presc_cnt_q >= presc_q) ? '0 : presc_cnt_q + 8'd1;
      presc_zero_d = presc_cnt_q >= presc_q;
    end
    if (!run_i || smp_valley) begin       // update mode and prescaler: before each valley (or idle)
      upd_valley_d = upd_in != UpdPeak;   // an invalid code (3) is a valley update (+ upd_err)
      upd_peak_d   = upd_in == UpdPeak || upd_in == UpdBoth;
      upd_err_d    = upd_in == 2'd3;
      presc_d      = presc_in;
    end
    if (!run_i) begin
      presc_cnt_d  = '0;
      presc_zero_d = 1'b1;
    end
  end

  // ---- calculator operands: loaded at its start (start_q: the clock after the sample) -----------
  logic                start_q, ev_valley_q;
  logic [CntWidth-1:0] calc_period_d, calc_period_q;
  logic [DtWidth:0]    calc_thr_d, calc_thr_q;
  logic [DtWidth-1:0]  calc_hdr_d, calc_hdr_q, calc_hdf_d, calc_hdf_q, hd_dt, hd_dtf, calc_dt_max;
  logic [DtWidth-1:0]  calc_mp;
  logic [3*EW-1:0]     carry_d, carry_q;
  logic [CntWidth-1:0] carry_per_d, carry_per_q;
  logic                carry_ok_d, carry_ok_q;

  assign hd_dt       = ev_valley_q ? dt_next_i : dt_i;
  assign hd_dtf      = ev_valley_q ? dtf_next_i : dtf_i;
  assign calc_dt_max = ev_valley_q ? (dtf_gt_next_i ? dtf_next_i : dt_next_i) : (dtf_gt_i ? dtf_i : dt_i);
  assign calc_mp     = ev_valley_q ? mp_next_i : mp_i;

  always_comb begin
    calc_period_d = calc_period_q;
    calc_thr_d    = calc_thr_q;
    calc_hdr_d    = calc_hdr_q;
    calc_hdf_d    = calc_hdf_q;
    carry_ok_d    = carry_ok_q;
    if (start_q) begin
      calc_period_d = ev_valley_q ? period_next_i : period_act_i;
      calc_thr_d    = {1'b0, calc_dt_max} + {1'b0, calc_mp};
      calc_hdr_d    = dtc_i ? DtWidth'(({1'b0, hd_dt} + 1'b1) >> 1) : '0;
      calc_hdf_d    = dtc_i ? DtWidth'(({1'b0, hd_dtf} + 1'b1) >> 1) : '0;
      carry_ok_d    = vsc_i && calc_period_d == carry_per_q;
    end
  end

  // ---- shadow and active registers ----------------------------------------------------------------
  logic [3*CntWidth-1:0] cmp_d, cmp_q;
  logic [2:0]            sector_d, sector_q;
  logic                  valid_d, valid_q, sat_d, sat_q, err_d, err_q, update_d, update_q;
  logic                  pending_d, pending_q, take;
  logic [1:0]            take_q;                // take, one and two clocks before

  // (point_i: load || pre_peak while running, from the carrier's flip-flops, not from run_i)
  assign take = upd_run_i && pending_q && calc_done_i && point_i;

  always_comb begin
    cmp_d       = cmp_q;
    sector_d    = sector_q;
    valid_d     = valid_q;
    sat_d       = sat_q;
    err_d       = err_q;
    update_d    = 1'b0;
    pending_d   = pending_q;
    carry_d     = carry_q;
    carry_per_d = carry_per_q;
    if (start_q) pending_d = 1'b1;
    if (!upd_run_i) begin                  // idle: nothing valid
      valid_d   = 1'b0;
      pending_d = 1'b0;
    end else begin
      if (take) begin                      // update point: all three phases together
        cmp_d     = calc_cmp_i;
        sector_d  = calc_sector_i;
        sat_d     = calc_sat_i;
        err_d     = calc_err_i;
        valid_d   = 1'b1;
        update_d  = 1'b1;
        pending_d = 1'b0;
      end
      if (take_q[1]) begin                 // the calculator's carry_o: valid two clocks after done_o
        carry_d     = vsc_i ? calc_carry_i : '0;
        carry_per_d = calc_period_q;
      end
    end
    if (!upd_run_i || trip_i) carry_d = '0; // a stop or a trip: no carry into the next start
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      upd_valley_q  <= 1'b1;
      upd_peak_q    <= 1'b0;
      presc_zero_q  <= 1'b1;
      upd_err_q     <= 1'b0;
      presc_q       <= '0;
      presc_cnt_q   <= '0;
      peak_cnt_q    <= '0;
      smp_valley_q  <= 1'b0;
      smp_peak_q    <= 1'b0;
      start_q       <= 1'b0;
      ev_valley_q   <= 1'b0;
      pending_q     <= 1'b0;
      calc_period_q <= CntWidth'(MinPeriod);
      calc_thr_q    <= '0;
      calc_hdr_q    <= '0;
      calc_hdf_q    <= '0;
      carry_ok_q    <= 1'b0;
      take_q        <= '0;
      carry_q       <= '0;
      carry_per_q   <= CntWidth'(MinPeriod);
      cmp_q         <= '0;
      sector_q      <= '0;
      valid_q       <= 1'b0;
      sat_q         <= 1'b0;
      err_q         <= 1'b0;
      update_q      <= 1'b0;
    end else begin
      upd_valley_q  <= upd_valley_d;
      upd_peak_q    <= upd_peak_d;
      presc_zero_q  <= presc_zero_d;
      upd_err_q     <= upd_err_d;
      presc_q       <= presc_d;
      presc_cnt_q   <= presc_cnt_d;
      peak_cnt_q    <= peak_cnt_d;
      smp_valley_q  <= smp_valley_d;
      smp_peak_q    <= smp_peak_d;
      start_q       <= run_i && sample;
      ev_valley_q   <= smp_valley;
      pending_q     <= pending_d;
      calc_period_q <= calc_period_d;
      calc_thr_q    <= calc_thr_d;
      calc_hdr_q    <= calc_hdr_d;
      calc_hdf_q    <= calc_hdf_d;
      carry_ok_q    <= carry_ok_d;
      take_q        <= {take_q[0], take};
      carry_q       <= carry_d;
      carry_per_q   <= carry_per_d;
      cmp_q         <= cmp_d;
      sector_q      <= sector_d;
      valid_q       <= valid_d;
      sat_q         <= sat_d;
      err_q         <= err_d;
      update_q      <= update_d;
    end
  end

  assign sample_o        = sample;
  assign smp_valley_o    = smp_valley;
  assign calc_start_o    = start_q && run_i;
  // a build without the peak / double update updates at valleys only (start_q implies ev_valley_q): the
  // calculator reads the next-period registers directly, which hold from the sample to the next valley's
  // sample (a whole period > the computation), and with one dead time dt_next + mp_next; calc_period_q /
  // calc_thr_q are then removed by synthesis (80 LC on the HX1K). Otherwise calc_period_q / calc_thr_q,
  // loaded at the start and valid from the first step on (the programs read them at step 2 at the
  // earliest: model/tests/test_calc_prog.py checks it)
  assign calc_period_o   = !HasUpd ? period_next_i : calc_period_q;
  assign calc_thr_o      = (!HasUpd && !HasDtf) ? {1'b0, dt_next_i} + {1'b0, mp_next_i} : calc_thr_q;
  assign calc_hdr_o      = calc_hdr_q;
  assign calc_hdf_o      = calc_hdf_q;
  assign calc_carry_o    = carry_q;        // (carry_q changes only after the computation's done_o)
  assign calc_carry_en_o = carry_ok_q;
  assign take_o          = take;
  assign cmp_o           = cmp_q;
  assign sector_o        = sector_q;
  assign valid_o         = valid_q;
  assign running_o       = en_i && run_i && valid_q;
  assign sat_o           = sat_q;
  assign err_o           = err_q || upd_err_q;
  assign update_o        = update_q;

`ifdef FORMAL
  // (proven in svpwm_core's formal/core.sby, with the core's reset assumption)
  // without the update modes the calculator reads period_next / dt_next + mp_next: valley updates only
  // (the update mode stays "valley", so every computation starts from a valley sample)
  always_comb if (!HasUpd && rst_ni) assert (upd_valley_q && !upd_peak_q);
  always_comb if (rst_ni) assert (presc_zero_q == (presc_cnt_q == '0));
  always_comb if (!HasUpd && rst_ni && start_q) assert (ev_valley_q);
  // the threshold is max(dt, dtf) + mp of the dead times the update is computed for
  if (HasDtf) begin : gen_f_dtf
    function automatic logic [DtWidth:0] f_thr(input logic [DtWidth-1:0] dt, input logic [DtWidth-1:0] dtf,
                                               input logic [DtWidth-1:0] mp);
      f_thr = {1'b0, (dt >= dtf) ? dt : dtf} + {1'b0, mp};
    endfunction
    always_comb if (rst_ni && start_q)
      assert (calc_thr_d == f_thr(ev_valley_q ? dt_next_i : dt_i, ev_valley_q ? dtf_next_i : dtf_i,
                                  ev_valley_q ? mp_next_i : mp_i));
  end
  always_comb cover (rst_ni && take);
`endif

endmodule

`default_nettype wire
