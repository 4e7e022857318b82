// SPDX-License-Identifier: Apache-2.0
// uart_tx: 8N1 UART transmitter. A byte offered with valid_i while ready_o is high is sent:
// start bit, 8 data bits LSB first, one stop bit; the start bit begins on the clock edge that takes it.
// Parameters: ClksPerBit - clocks per bit (>= 2).
// Timing: ready_o and tx_o are flip-flops; the bit timer counts down to -1 (its sign bit ends a bit),
// so no wide compare sits between the timer and the enables.
`default_nettype none

module uart_tx #(
  parameter int ClksPerBit = 417
) (
  input  wire        clk_i,
  input  wire        rst_ni,
  input  wire  [7:0] data_i,
  input  wire        valid_i,
  output logic       ready_o,       // idle, a byte may be offered
  output logic       tx_o           // serial output, idle high
);
  localparam int CW = $clog2(ClksPerBit) + 1;   // ClksPerBit - 2 and a sign bit

  if (ClksPerBit < 2) begin : gen_bad
`ifdef __ICARUS__  // Icarus 11 has no elaboration-time tasks: at time 0
    initial $fatal(1, "uart_tx: ClksPerBit must be >= 2, got %0d (%m)", ClksPerBit);
`else              // at elaboration (Yosys formats $display only, then stops at $error)
    initial $display("uart_tx: ClksPerBit must be >= 2, got %0d (%m)", ClksPerBit);
    $error("uart_tx: ClksPerBit must be >= 2, got %0d", ClksPerBit);
`endif
  end

  logic [9:0]    sh_d, sh_q;        // {stop, data, start}, shifted out LSB first; all ones when idle
  logic [3:0]    left_d, left_q;    // bits still to send
  logic [CW-1:0] cnt_d, cnt_q;      // clocks left in the bit minus 2: the bit ends at -1 (cnt_q[CW-1])
  logic          ready_d, ready_q;  // left_q == 0

  always_comb begin
    sh_d    = sh_q;
    left_d  = left_q;
    cnt_d   = cnt_q - 1'b1;           // runs freely while idle: loaded with every byte
    ready_d = ready_q;
    if (ready_q) begin
      if (valid_i) begin
        sh_d    = {1'b1, data_i, 1'b0};
        left_d  = 4'd10;
        cnt_d   = CW'(ClksPerBit - 2);
        ready_d = 1'b0;
      end
    end else if (cnt_q[CW-1]) begin   // end of a bit
      sh_d    = {1'b1, sh_q[9:1]};
      left_d  = left_q - 1'b1;
      cnt_d   = CW'(ClksPerBit - 2);
      ready_d = (left_q == 4'd1);
    end
  end

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      sh_q    <= '1;
      left_q  <= '0;
      cnt_q   <= '0;
      ready_q <= 1'b1;
    end else begin
      sh_q    <= sh_d;
      left_q  <= left_d;
      cnt_q   <= cnt_d;
      ready_q <= ready_d;
    end
  end

  assign ready_o = ready_q;
  assign tx_o    = sh_q[0];           // the stop bit and idle shift ones in: high when idle
endmodule

`default_nettype wire
