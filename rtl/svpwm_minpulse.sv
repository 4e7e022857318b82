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

  logic [1:0]            st_d, st_q;       // 0 idle, 1..3: phase a, b, c
  logic                  run_d, run_q, done_d, done_q;
  logic [3*CntWidth-1:0] cmp_d, cmp_q;
  logic [CntWidth-1:0]   p_d, p_q, thr_d, thr_q, hthr, c, rest, c_new;

  assign hthr = (thr_q + 1'b1) >> 1;

  always_comb begin
    st_d   = st_q;
    run_d  = run_q;
    cmp_d  = cmp_q;
    p_d    = p_q;
    thr_d  = thr_q;
    done_d = 1'b0;
    c      = cmp_q[st_q*CntWidth +: CntWidth];
    rest   = p_q - c;
    c_new  = c;
    if (c < thr_q) begin
      c_new = ({c, 1'b0} < {1'b0, thr_q}) ? '0 : thr_q;
    end else if (rest < hthr) begin
      c_new = ({rest, 1'b0} < {1'b0, hthr}) ? p_q : p_q - hthr;
    end
    if (start_i) begin
      st_d  = 2'd0;
      run_d = 1'b1;
      cmp_d = cmp_i;
      p_d   = period_i;
      thr_d = CntWidth'(thr_i);
    end else if (run_q) begin
      cmp_d[st_q*CntWidth +: CntWidth] = c_new;
      st_d = st_q + 2'd1;
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
    end else begin
      st_q   <= st_d;
      run_q  <= run_d;
      done_q <= done_d;
      cmp_q  <= cmp_d;
      p_q    <= p_d;
      thr_q  <= thr_d;
    end
  end

  assign done_o = done_q;
  assign cmp_o  = cmp_q;

endmodule

`default_nettype wire
