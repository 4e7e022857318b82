// SPDX-License-Identifier: Apache-2.0
// uart_tx: 8N1 UART transmitter. A byte offered with valid_i while ready_o is high is sent:
// start bit, 8 data bits LSB first, one stop bit. Parameters: ClksPerBit - clocks per bit (>= 2).
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
  localparam int CW = $clog2(ClksPerBit + 1);

  logic [9:0]    sh_q;              // {stop, data, start}, shifted out LSB first
  logic [3:0]    left_q;            // bits still to send
  logic [CW-1:0] cnt_q;

  always_ff @(posedge clk_i or negedge rst_ni) begin
    if (!rst_ni) begin
      sh_q   <= '1;
      left_q <= '0;
      cnt_q  <= '0;
    end else if (left_q == '0) begin
      if (valid_i) begin
        sh_q   <= {1'b1, data_i, 1'b0};
        left_q <= 4'd10;
        cnt_q  <= CW'(ClksPerBit - 1);
      end
    end else if (cnt_q != '0) begin
      cnt_q <= cnt_q - 1'b1;
    end else begin
      sh_q   <= {1'b1, sh_q[9:1]};
      left_q <= left_q - 1'b1;
      cnt_q  <= CW'(ClksPerBit - 1);
    end
  end

  assign ready_o = (left_q == '0);
  assign tx_o    = (left_q == '0) ? 1'b1 : sh_q[0];
endmodule

`default_nettype wire
