// SPDX-License-Identifier: Apache-2.0
// svpwm_adc: current sampling support of svpwm_core (feature ADC): two programmable ADC trigger points
// and the per-phase shunt-window report (model: svpwm_model/adc.py, docs/reference.md "Current sampling").
// Trigger points: point k fires (pt_o[k], one clock, registered: in the clock after) once per carrier
// period while the carrier runs, at the clock where the carrier is at count cnt_k counting up (dn_k = 0)
// or down (dn_k = 1); the valley (count 0) and the peak (count P) are one clock each and fire for either
// direction, and a count beyond the active half period P fires at the peak. The points (en, dn, cnt)
// and the minimum window are sampled with the reference (sample_i: the core's sample clock) and take
// effect with the compare values computed from it (take_i: the update), like a shadow / active register
// pair, so the trigger points of a period are those of its compare values; none fire while stopped and
// before the first update of a run.
// Shunt-window report, per phase x from the active compare value C, half period P, dead times dt (rising:
// before a high side) and dtf (falling: before a low side) and minimum pulse mp in force: the gates'
// on-times in the steady state of a period whose neighbours have the same values (svpwm_model/adc.py,
// on_times; a gate once on stays on H = max(dt, dtf, mp, 1) clocks), with Dh = 2(P - C), Dl = 2C:
//   C == P: lo = 2P, hi = 0;  C == 0: lo = 0, hi = 2P;  else h1 = max(Dh, dt + H),
//   hi = h1 - dt (the high side around the peak: Dh - dt, or H when it is held on),
//   lo = 2P - h1 - dtf (the low side around the valley: Dl - dtf, shortened by a held high side); the low
//   side is never held (the minimum-pulse rule keeps Dl >= 2 (max(dt, dtf) + mp) >= dtf + H)
//   win_ok[x] = win_lo[x] >= max(the minimum window, 1) (the ADC's settling + acquisition around its
//               sample point: readable with a low-side shunt)
//   win_recon = the phase with the shortest low-side window (the first of equal ones): read the other two
//               and reconstruct it as minus their sum (i_a + i_b + i_c = 0)
// all zero while the compare values are not valid (active_i low: stopped or tripped).
// Parameters: CntWidth - carrier width (svpwm_core's), DtWidth - dead-time width.
// Latency: pt_o one clock after the carrier was at the point (a register).
// The report is computed one phase per clock (a 3-stage pipeline, the phases in turn): win_lo_o /
// win_hi_o show a change of the active values, dead times, minimum pulse or period after at most 8 clocks,
// win_ok_o / win_recon_o after at most 9 (the core's report at 9 clocks after each valley and peak is what
// tb/cocotb/svpwm_core/test_svpwm_adc.py compares with the model).
`default_nettype none

module svpwm_adc #(
  parameter int CntWidth = 16,
  parameter int DtWidth  = 10
) (
  input  logic                      clk_i,         // core clock
  input  logic                      rst_ni,        // asynchronous reset, active low
  input  logic                      run_i,         // the carrier runs (the core's run_q)
  input  logic [CntWidth-1:0]       count_i,       // carrier value
  input  logic                      up_i,          // carrier counting up
  input  logic                      valley_i,      // running and count == 0
  input  logic                      peak_i,        // running and count == P
  input  logic [CntWidth-1:0]       period_i,      // active half period P
  input  logic                      sample_i,      // the reference is sampled (the core's event_now)
  input  logic                      take_i,        // the update: compare values computed from it active
  input  logic [1:0]                pt_en_i,       // trigger point k enabled
  input  logic [1:0]                pt_dn_i,       // trigger point k on the down count
  input  logic [2*CntWidth-1:0]     pt_cnt_i,      // {cnt_1, cnt_0}: carrier counts of the points
  input  logic [CntWidth:0]         win_min_i,     // minimum low-side window, clocks
  input  logic                      active_i,      // active compare values valid (running, not tripped)
  input  logic [3*CntWidth-1:0]     cmp_i,         // {C_c, C_b, C_a} active
  input  logic [DtWidth-1:0]        dt_i,          // rising dead time in force
  input  logic [DtWidth-1:0]        dtf_i,         // falling dead time in force
  input  logic [DtWidth-1:0]        mp_i,          // minimum pulse in force
  output logic [1:0]                pt_o,          // pulse: trigger point k
  output logic [3*(CntWidth+1)-1:0] win_lo_o,      // {c, b, a} low-side windows, clocks
  output logic [3*(CntWidth+1)-1:0] win_hi_o,      // {c, b, a} high-side windows, clocks
  output logic [2:0]                win_ok_o,      // {c, b, a} low-side window >= the minimum
  output logic [1:0]                win_recon_o    // the phase to reconstruct (0 a, 1 b, 2 c)
);

  localparam int WW = CntWidth + 1;

  // ---- trigger points: sampled with the reference, active from its update ------------------------
  logic [1:0]            en_smp_d, en_smp_q, dn_smp_d, dn_smp_q, en_act_d, en_act_q, dn_act_d, dn_act_q;
  logic [2*CntWidth-1:0] cnt_smp_d, cnt_smp_q, cnt_act_d, cnt_act_q;
  logic [WW-1:0]         min_smp_d, min_smp_q, min_act_d, min_act_q;

  always_comb begin
    en_smp_d  = en_smp_q;
    dn_smp_d  = dn_smp_q;
    cnt_smp_d = cnt_smp_q;
    min_smp_d = min_smp_q;
    en_act_d  = en_act_q;
    dn_act_d  = dn_act_q;
    cnt_act_d = cnt_act_q;
    min_act_d = min_act_q;
    if (sample_i) begin
      en_smp_d  = pt_en_i;
      dn_smp_d  = pt_dn_i;
      cnt_smp_d = pt_cnt_i;
      min_smp_d = win_min_i;
    end
    if (take_i) begin
      en_act_d  = en_smp_q;
      dn_act_d  = dn_smp_q;
      cnt_act_d = cnt_smp_q;
      min_act_d = min_smp_q;
    end
    if (!run_i) en_act_d = '0;        // stopped: no point until the next run's first update
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      en_smp_q  <= '0;
      dn_smp_q  <= '0;
      cnt_smp_q <= '0;
      min_smp_q <= '0;
      en_act_q  <= '0;
      dn_act_q  <= '0;
      cnt_act_q <= '0;
      min_act_q <= '0;
    end else begin
      en_smp_q  <= en_smp_d;
      dn_smp_q  <= dn_smp_d;
      cnt_smp_q <= cnt_smp_d;
      min_smp_q <= min_smp_d;
      en_act_q  <= en_act_d;
      dn_act_q  <= dn_act_d;
      cnt_act_q <= cnt_act_d;
      min_act_q <= min_act_d;
    end
  end

  // the pulse is registered: it comes in the clock after the carrier was at the point (a clean output
  // for an ADC's start input, and no carrier compare on the path to a pin)
  logic [1:0] pt_d, pt_q;

  for (genvar k = 0; k < 2; k++) begin : gen_point
    logic [CntWidth-1:0] cnt;
    assign cnt     = cnt_act_q[k*CntWidth +: CntWidth];
    assign pt_d[k] = en_act_q[k] && ((run_i && count_i == cnt && up_i == !dn_act_q[k])
                                     || (peak_i && cnt >= period_i) || (valley_i && cnt == '0));
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) pt_q <= '0;
    else         pt_q <= pt_d;
  end

  assign pt_o = pt_q;

  // ---- shunt-window report: one phase at a time through a 3-stage pipeline (phase_q turns 0, 1, 2 every
  // clock), so one datapath serves the three phases (svpwm_model/adc.py: on_times) -----------------
  localparam int DW = DtWidth + 1;

  // the shared terms, registered step by step (the core's dead-time registers are far away): the inputs,
  // max(dt, dtf), H = max(dt, dtf, mp, 1), then dt + H and 2P - dtf
  logic [DtWidth-1:0]  dt1_q, dtf1_q, mp1_q, m_d, m_q, h_d, h_q;
  logic                hz_d, hz_q;
  logic [CntWidth-1:0] p1_q;
  logic [DW-1:0]       kdh_d, kdh_q;
  logic [WW-1:0]       k2p_d, k2p_q, lob_d, lob_q, p2;

  assign m_d = (dt1_q >= dtf1_q) ? dt1_q : dtf1_q;
  // (the floor of 1 beside the max, not after it: H = 0 only when mp and max(dt, dtf) are 0)
  assign h_d   = (mp1_q > m_q) ? mp1_q : m_q;
  assign hz_d  = mp1_q == '0 && m_q == '0;
  assign kdh_d = {1'b0, dt1_q} + {1'b0, h_q | DtWidth'(hz_q)};
  assign k2p_d = {p1_q, 1'b0} - WW'(dtf1_q);
  assign p2    = {p1_q, 1'b0};                     // 2P (a wire: no register of its own)
  assign lob_d = k2p_q - WW'(kdh_q);               // the low side's window after a held high side

  // stage 1: the phase's high pole pulse Dh = 2(P - C) (the low side is never held past the pole's rise:
  // r = 0, since the minimum-pulse rule keeps 2C >= 2 (max(dt, dtf) + mp) >= dtf + H)
  logic [1:0]          phase_d, phase_q, ph1_q, ph2_q;
  logic [CntWidth-1:0] c1;
  logic [WW-1:0]       dh1_d, dh1_q;
  logic                full_lo1_d, full_lo1_q, full_hi1_d, full_hi1_q;

  assign phase_d    = (phase_q == 2'd2) ? 2'd0 : phase_q + 2'd1;
  // (a case, not an indexed part-select: Yosys builds the index product as an adder chain)
  always_comb begin
    unique case (phase_q)
      2'd1:    c1 = cmp_i[CntWidth +: CntWidth];
      2'd2:    c1 = cmp_i[2*CntWidth +: CntWidth];
      default: c1 = cmp_i[0 +: CntWidth];
    endcase
  end
  assign dh1_d      = {p1_q - c1, 1'b0};
  assign full_lo1_d = c1 == p1_q;                   // low side on the whole period
  assign full_hi1_d = c1 == '0;

  // stage 2: the high side off at h1 = max(Dh, dt + H) (held on for H): both outcomes, then the compare
  // (the subtracts beside the compare, so stage 3 only selects)
  logic [WW-1:0] loa2_d, loa2_q, hia2_d, hia2_q;
  logic          ge2_d, ge2_q, full_lo2_q, full_hi2_q, act2_q, act1_q;

  assign ge2_d  = dh1_q >= WW'(kdh_q);              // h1 = Dh
  assign loa2_d = k2p_q - dh1_q;                    // 2P - Dh - dtf = 2C - dtf
  assign hia2_d = dh1_q - WW'(dt1_q);               // Dh - dt

  // stage 3: hi = h1 - dt, lo = 2P - h1 - dtf into the phase's result registers
  logic [3*WW-1:0] lo_d, lo_q, hi_d, hi_q;
  logic [WW-1:0]   lo3, hi3;

  assign lo3 = !act2_q ? '0 : full_lo2_q ? p2 : full_hi2_q ? '0 : ge2_q ? loa2_q : lob_q;
  assign hi3 = !act2_q ? '0 : full_lo2_q ? '0 : full_hi2_q ? p2
             : ge2_q ? hia2_q : WW'(h_q | DtWidth'(hz_q));

  for (genvar ph = 0; ph < 3; ph++) begin : gen_result
    assign lo_d[ph*WW +: WW] = (ph2_q == 2'(ph)) ? lo3 : lo_q[ph*WW +: WW];
    assign hi_d[ph*WW +: WW] = (ph2_q == 2'(ph)) ? hi3 : hi_q[ph*WW +: WW];
  end

  // the readable mask and the phase to reconstruct, from the results
  logic [2:0]    ok_d, ok_q;
  logic [1:0]    recon_d, recon_q;
  logic [WW-1:0] lo_a, lo_b, lo_c;

  for (genvar ph = 0; ph < 3; ph++) begin : gen_ok
    assign ok_d[ph] = lo_q[ph*WW +: WW] != '0 && lo_q[ph*WW +: WW] >= min_act_q;
  end
  assign lo_a    = lo_q[0 +: WW];
  assign lo_b    = lo_q[WW +: WW];
  assign lo_c    = lo_q[2*WW +: WW];
  assign recon_d = (lo_a <= lo_b && lo_a <= lo_c) ? 2'd0 : (lo_b <= lo_c) ? 2'd1 : 2'd2;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      h_q        <= '0;
      hz_q       <= 1'b1;
      m_q        <= '0;
      dt1_q      <= '0;
      dtf1_q     <= '0;
      mp1_q      <= '0;
      p1_q       <= '0;
      kdh_q      <= '0;
      k2p_q      <= '0;
      phase_q    <= '0;
      ph1_q      <= '0;
      ph2_q      <= '0;
      dh1_q      <= '0;
      full_lo1_q <= 1'b0;
      full_hi1_q <= 1'b0;
      act1_q     <= 1'b0;
      ge2_q      <= 1'b0;
      loa2_q     <= '0;
      hia2_q     <= '0;
      lob_q      <= '0;
      full_lo2_q <= 1'b0;
      full_hi2_q <= 1'b0;
      act2_q     <= 1'b0;
      lo_q       <= '0;
      hi_q       <= '0;
      ok_q       <= '0;
      recon_q    <= '0;
    end else begin
      h_q        <= h_d;
      hz_q       <= hz_d;
      m_q        <= m_d;
      dt1_q      <= dt_i;
      dtf1_q     <= dtf_i;
      mp1_q      <= mp_i;
      p1_q       <= period_i;
      kdh_q      <= kdh_d;
      k2p_q      <= k2p_d;
      phase_q    <= phase_d;
      ph1_q      <= phase_q;
      ph2_q      <= ph1_q;
      dh1_q      <= dh1_d;
      full_lo1_q <= full_lo1_d;
      full_hi1_q <= full_hi1_d;
      act1_q     <= active_i;
      ge2_q      <= ge2_d;
      loa2_q     <= loa2_d;
      hia2_q     <= hia2_d;
      lob_q      <= lob_d;
      full_lo2_q <= full_lo1_q;
      full_hi2_q <= full_hi1_q;
      act2_q     <= act1_q;
      lo_q       <= lo_d;
      hi_q       <= hi_d;
      ok_q       <= ok_d;
      recon_q    <= recon_d;
    end
  end

  assign win_lo_o    = lo_q;
  assign win_hi_o    = hi_q;
  assign win_ok_o    = ok_q;
  assign win_recon_o = recon_q;

endmodule

`default_nettype wire
