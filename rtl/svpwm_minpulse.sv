// SPDX-License-Identifier: Apache-2.0
// svpwm_minpulse: minimum-pulse rule on the three compare values, one phase per clock.
// A pole pulse shorter than thr = dead time + minimum pulse would reach its gate shorter than the
// minimum pulse (the dead time eats dt of it); such pulses are dropped or widened to thr, whichever is
// nearer, so no gate ever sees a runt:
//   low pulse around the valley (C of the two periods it straddles): C in (0, thr) -> 0 or thr;
//   high pulse around the peak (2 (P - C) clocks): P - C in (0, ceil(thr/2)) -> P or P - ceil(thr/2).
// The map is monotonic: the order of the phases, i.e. the Table I sequence, is kept (states may only
// be skipped). Model: model/svpwm_model/fixed.py:snap_min_pulse().
// Parameters: CntWidth - compare / period width; DtWidth - dead-time and minimum-pulse width.
// Latency: 4 clocks from start_i to done_o. Restrictions: period_i >= 2 * thr_i (svpwm_core clamps).
`default_nettype none

module svpwm_minpulse #(
  parameter int CntWidth = 16,
  parameter int DtWidth  = 10
) (
  input  logic                  clk_i,      // core clock
  input  logic                  rst_ni,     // asynchronous reset, active low
  input  logic                  start_i,    // take cmp_i, period_i, thr_i
  input  logic [3*CntWidth-1:0] cmp_i,      // {C_c, C_b, C_a} from svpwm_duty
  input  logic [CntWidth-1:0]   period_i,   // half period P the values belong to
  input  logic [DtWidth:0]      thr_i,      // dead time + minimum pulse, clocks
  output logic                  done_o,     // one-cycle pulse: cmp_o is new
  output logic [3*CntWidth-1:0] cmp_o       // snapped compare values
);

  if (DtWidth + 2 > CntWidth) begin : gen_bad_width
    initial $fatal(1, "svpwm_minpulse: need DtWidth + 2 <= CntWidth, got %0d / %0d", DtWidth, CntWidth);
  end

  // Each step compares the phase value c = cmp_q[0 +: CntWidth] against thresholds precomputed at the
  // start (no subtraction in the loop), writes the result in at the top and rotates, so after three
  // steps the phases are back in order:
  //   c < thr                       -> 0 (2c < thr) or thr
  //   P - c < hthr  <=>  c > P - hthr  -> P (2 (P - c) < hthr  <=>  2c > 2P - hthr) or P - hthr
  logic [1:0]            st_d, st_q;       // steps done
  logic                  run_d, run_q, done_d, done_q;
  logic [3*CntWidth-1:0] cmp_d, cmp_q;
  logic [CntWidth-1:0]   p_d, p_q, thr_d, thr_q, top_d, top_q, c, c_new, hthr;
  logic [CntWidth:0]     twop_d, twop_q;   // 2P - hthr
  logic [CntWidth-1:0]   p_hthr;           // P - hthr

  assign hthr   = (CntWidth'(thr_i) + 1'b1) >> 1;
  assign p_hthr = period_i - hthr;
  assign c      = cmp_q[CntWidth-1:0];

  always_comb begin
    st_d   = st_q;
    run_d  = run_q;
    cmp_d  = cmp_q;
    p_d    = p_q;
    thr_d  = thr_q;
    top_d  = top_q;
    twop_d = twop_q;
    done_d = 1'b0;
    c_new  = c;
    if (c < thr_q) begin
      c_new = ({c, 1'b0} < {1'b0, thr_q}) ? '0 : thr_q;
    end else if (c > top_q) begin
      c_new = ({c, 1'b0} > twop_q) ? p_q : top_q;
    end
    if (start_i) begin
      st_d   = 2'd0;
      run_d  = 1'b1;
      cmp_d  = cmp_i;
      p_d    = period_i;
      thr_d  = CntWidth'(thr_i);
      top_d  = p_hthr;
      twop_d = {period_i, 1'b0} - {1'b0, hthr};
    end else if (run_q) begin
      cmp_d = {c_new, cmp_q[3*CntWidth-1:CntWidth]};   // rotate: the next phase comes to the bottom
      st_d  = st_q + 2'd1;
      if (st_q == 2'd2) begin
        run_d  = 1'b0;
        done_d = 1'b1;
        st_d   = 2'd0;
      end
    end
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      st_q   <= '0;
      run_q  <= 1'b0;
      done_q <= 1'b0;
      cmp_q  <= '0;
      p_q    <= '0;
      thr_q  <= '0;
      top_q  <= '0;
      twop_q <= '0;
    end else begin
      st_q   <= st_d;
      run_q  <= run_d;
      done_q <= done_d;
      cmp_q  <= cmp_d;
      p_q    <= p_d;
      thr_q  <= thr_d;
      top_q  <= top_d;
      twop_q <= twop_d;
    end
  end

  assign done_o = done_q;
  assign cmp_o  = cmp_q;

endmodule

`default_nettype wire
