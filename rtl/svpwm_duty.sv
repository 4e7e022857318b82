// SPDX-License-Identifier: Apache-2.0
// svpwm_duty: multiplier-based duty calculator, angle + m + period -> three compare values.
// d_a = m sin(60 deg - theta'), d_b = m sin(theta')  (Minas eq. (4), AVR495 sec. 4.2, Verma (29)-(30));
// C = P/2 * (1 + k), k = +-d_a +- d_b per sector (AVR495 Table 4-3), which gives the symmetric
// seven-segment pattern of Minas eq. (6)/(7) and Table I: V0 split at both ends, V7 in the middle.
// sin() comes from sine_rom by linear interpolation between its 0..60 deg points, so the 16-bit
// in-sector angle (0.0009 deg) is used in full. One 16x16 multiplier (one iCE40 DSP) is time-shared
// by an 11-step sequence: 2 interpolations, 2 products m*sin, 2 products d*P, then the sums.
// Arithmetic: exactly model/svpwm_model/fixed.py:compare_values() (the golden model).
// Parameters: CntWidth - period / compare width (8..16).
// Latency: 12 clocks from start_i to done_o; outputs hold until the next done_o.
// Restrictions: m_i <= 0x8000 (1.0) -- svpwm_core clamps it; start_i is ignored while busy_o.
`default_nettype none

module svpwm_duty #(
  parameter int CntWidth = 16
) (
  input  logic                  clk_i,      // core clock
  input  logic                  rst_ni,     // asynchronous reset, active low
  input  logic                  start_i,    // sample the inputs below and start
  input  logic [2:0]            sector_i,   // 0..5
  input  logic [15:0]           angle_i,    // theta' / 60 deg, UQ0.16 (8-bit ROM index + 8-bit fraction)
  input  logic [15:0]           m_i,        // modulation index, UQ1.15, <= 0x8000
  input  logic [CntWidth-1:0]   period_i,   // half carrier period P the compare values are scaled to
  output logic                  busy_o,     // a computation is running
  output logic                  done_o,     // one-cycle pulse: the outputs below are new
  output logic [2:0]            sector_o,   // sector of the result
  output logic [3*CntWidth-1:0] cmp_o       // {C_c, C_b, C_a}, each in [0, P]
);

  localparam int KFrac   = 8;                    // fraction bits kept of P*d (model K_FRAC)
  localparam int KWidth  = CntWidth + KFrac + 3;  // signed width of (P+1)*2^KFrac +- (A +- B)

  if (CntWidth < 8 || CntWidth > 16) begin : gen_bad_width
    initial $fatal(1, "svpwm_duty: CntWidth must be 8..16, got %0d", CntWidth);
  end

  // ---- state -------------------------------------------------------------------------------------
  logic [3:0]            st_d, st_q;           // 0 idle, 1..11 steps
  logic [2:0]            sector_d, sector_q, sector_out_d, sector_out_q;
  logic [7:0]            idx_d, idx_q, fr_d, fr_q;
  logic [15:0]           m_d, m_q;
  logic [CntWidth-1:0]   p_d, p_q;
  logic [15:0]           r0_d, r0_q;           // R[idx], later R[256-idx]
  logic [15:0]           sb_d, sb_q, sa_d, sa_q, db_d, db_q, da_d, da_q;
  logic [CntWidth+7:0]   b8_d, b8_q;           // (d_b * P) >> 8
  logic [CntWidth+9:0]   sum_d, sum_q, dif_d, dif_q;   // A + B, A - B (signed), registered
  logic [31:0]           prod_d, prod_q;       // the shared multiplier's registered product
  logic [3*CntWidth-1:0] cmp_d, cmp_q;
  logic                  done_d, done_q;

  // ---- sine ROM ----------------------------------------------------------------------------------
  logic [8:0]  rom_addr;
  logic [15:0] rom_data;

  sine_rom u_rom (
    .clk_i  (clk_i),
    .addr_i (rom_addr),
    .data_o (rom_data)
  );

  always_comb begin
    unique case (st_q)
      4'd1:    rom_addr = {1'b0, idx_q};                 // R[idx]
      4'd2:    rom_addr = {1'b0, idx_q} + 9'd1;          // R[idx+1]
      4'd3:    rom_addr = 9'd256 - {1'b0, idx_q};        // R[256-idx]
      4'd4:    rom_addr = 9'd255 - {1'b0, idx_q};        // R[255-idx]
      default: rom_addr = '0;
    endcase
  end

  // ---- shared multiplier ------------------------------------------------------------------------
  logic [15:0] mul_a, mul_b;

  always_comb begin
    mul_a = '0;
    mul_b = '0;
    unique case (st_q)
      4'd3:    begin mul_a = rom_data - r0_q; mul_b = {8'd0, fr_q}; end   // (R[idx+1]-R[idx]) * fr
      4'd5:    begin mul_a = r0_q - rom_data; mul_b = {8'd0, fr_q}; end   // (R[256-idx]-R[255-idx]) * fr
      4'd6:    begin mul_a = m_q;  mul_b = sb_q; end                      // m * sin(theta')
      4'd7:    begin mul_a = m_q;  mul_b = sa_q; end                      // m * sin(60-theta')
      4'd8:    begin mul_a = db_q; mul_b = 16'(p_q); end                  // d_b * P
      4'd9:    begin mul_a = da_q; mul_b = 16'(p_q); end                  // d_a * P
      default: ;
    endcase
  end

  assign prod_d = mul_a * mul_b;

  // ---- compare values: AVR495 Table 4-3 ----------------------------------------------------------
  // selection per phase: 0: +(A+B)  1: -(A+B)  2: +(A-B)  3: -(A-B), A = d_a P, B = d_b P
  function automatic logic [5:0] sector_sel(input logic [2:0] s);
    unique case (s)
      3'd0:    sector_sel = {2'd0, 2'd2, 2'd1};   // sector 1: a -da-db, b da-db, c da+db
      3'd1:    sector_sel = {2'd0, 2'd1, 2'd3};   // sector 2: a -da+db, b -da-db, c da+db
      3'd2:    sector_sel = {2'd2, 2'd1, 2'd0};   // sector 3: a da+db, b -da-db, c da-db
      3'd3:    sector_sel = {2'd1, 2'd3, 2'd0};   // sector 4: a da+db, b -da+db, c -da-db
      3'd4:    sector_sel = {2'd1, 2'd0, 2'd2};   // sector 5: a da-db, b da+db, c -da-db
      default: sector_sel = {2'd3, 2'd0, 2'd1};   // sector 6: a -da-db, b da+db, c -da+db
    endcase
  endfunction

  logic signed [KWidth-1:0] a8s, b8s, sum_ab, dif_ab, base, c_x;
  logic [5:0]               sel;

  // step 10: A + B and A - B from this cycle's product (A) and the stored B; step 11: per phase
  // C = ((P + 1) << 8 +- (A + B or A - B)) >> 9 -- one add/subtract each, so no adder chains.
  always_comb begin
    a8s    = KWidth'(prod_q[CntWidth+15:8]);                 // (d_a * P) >> 8, product of step 9
    b8s    = KWidth'(b8_q);
    sum_d  = (st_q == 4'd10) ? (CntWidth+10)'(a8s + b8s) : sum_q;
    dif_d  = (st_q == 4'd10) ? (CntWidth+10)'(a8s - b8s) : dif_q;
    sum_ab = KWidth'($signed(sum_q));
    dif_ab = KWidth'($signed(dif_q));
    base   = KWidth'({p_q, 8'd0}) + KWidth'(9'd256);        // (P + 1) << 8
    sel    = sector_sel(sector_q);
    cmp_d  = cmp_q;
    c_x    = '0;
    if (st_q == 4'd11) begin
      for (int ph = 0; ph < 3; ph++) begin
        unique case (sel[2*ph +: 2])
          2'd0:    c_x = base + sum_ab;
          2'd1:    c_x = base - sum_ab;
          2'd2:    c_x = base + dif_ab;
          default: c_x = base - dif_ab;
        endcase
        c_x = c_x >>> (KFrac + 1);
        cmp_d[ph*CntWidth +: CntWidth] = c_x[CntWidth-1:0];
      end
    end
  end

  logic unused_cx;
  assign unused_cx = ^c_x[KWidth-1:CntWidth];   // c_x is in [0, P] (see model bound test)

  // ---- sequence ----------------------------------------------------------------------------------
  always_comb begin
    st_d         = st_q;
    sector_d     = sector_q;
    idx_d        = idx_q;
    fr_d         = fr_q;
    m_d          = m_q;
    p_d          = p_q;
    r0_d         = r0_q;
    sb_d         = sb_q;
    sa_d         = sa_q;
    db_d         = db_q;
    da_d         = da_q;
    b8_d         = b8_q;
    sector_out_d = sector_out_q;
    done_d       = 1'b0;
    unique case (st_q)
      4'd0: begin
        if (start_i) begin
          st_d     = 4'd1;
          sector_d = sector_i;
          idx_d    = angle_i[15:8];
          fr_d     = angle_i[7:0];
          m_d      = m_i;
          p_d      = period_i;
        end
      end
      4'd2:  r0_d = rom_data;                                              // R[idx]
      4'd3:  ;                                                             // product (R[idx+1]-R[idx])*fr
      4'd4: begin
        sb_d = r0_q + 16'((prod_q + 32'd128) >> 8);                        // sin(theta')
        r0_d = rom_data;                                                   // R[256-idx]
      end
      4'd5:  ;                                                             // product (R[256-idx]-R[255-idx])*fr
      4'd6:  sa_d = r0_q - 16'((prod_q + 32'd128) >> 8);                   // sin(60 - theta')
      4'd7:  db_d = 16'((prod_q + 32'd16384) >> 15);                       // d_b, UQ0.16
      4'd8:  da_d = 16'((prod_q + 32'd16384) >> 15);                       // d_a, UQ0.16
      4'd9:  b8_d = prod_q[CntWidth+15:8];                                 // (d_b * P) >> 8
      4'd10: ;                                                             // A + B, A - B (above)
      4'd11: begin                                                         // compare values (above)
        sector_out_d = sector_q;
        done_d       = 1'b1;
      end
      default: ;
    endcase
    if (st_q != 4'd0) st_d = (st_q == 4'd11) ? 4'd0 : st_q + 4'd1;
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      st_q         <= '0;
      sector_q     <= '0;
      idx_q        <= '0;
      fr_q         <= '0;
      m_q          <= '0;
      p_q          <= '0;
      r0_q         <= '0;
      sb_q         <= '0;
      sa_q         <= '0;
      db_q         <= '0;
      da_q         <= '0;
      b8_q         <= '0;
      sum_q        <= '0;
      dif_q        <= '0;
      prod_q       <= '0;
      cmp_q        <= '0;
      sector_out_q <= '0;
      done_q       <= 1'b0;
    end else begin
      st_q         <= st_d;
      sector_q     <= sector_d;
      idx_q        <= idx_d;
      fr_q         <= fr_d;
      m_q          <= m_d;
      p_q          <= p_d;
      r0_q         <= r0_d;
      sb_q         <= sb_d;
      sa_q         <= sa_d;
      db_q         <= db_d;
      da_q         <= da_d;
      b8_q         <= b8_d;
      sum_q        <= sum_d;
      dif_q        <= dif_d;
      prod_q       <= prod_d;
      cmp_q        <= cmp_d;
      sector_out_q <= sector_out_d;
      done_q       <= done_d;
    end
  end

  assign busy_o   = st_q != 4'd0;
  assign done_o   = done_q;
  assign sector_o = sector_out_q;
  assign cmp_o    = cmp_q;

endmodule

`default_nettype wire
